#pragma once
/** @file box_router.h
 * feature_labels = boxes (issue 31, item 2; doc/boxes.md): the router of a detector's boxes
 * without IDs. Each step, the step's boxes (TRouterContext::boxes; in the rawlog, the
 * DETECTION_BOXES comment, dynslam/common/detection_boxes.h) are placed in the world with the
 * filter's ego predicted by the step's odometry, and a CBoxTracker (box_tracker.h) associates them
 * with its tracks (the joint part: a track the filter holds is predicted by the filter,
 * TRouterContext::box_prediction). The four corner readings (ID -1, hint = the box's group) of
 * a box whose track is Confirmed after the update get the persistent IDs
 * cornerId(track, c), c the corner in the track's own order (a flipped box's corners are
 * turned by two), and the track as their hint; the corners of boxes of Tentative tracks or
 * ignored boxes (score below box_min_score) are dropped (TRoutedStep::skipped_box_corners): a
 * false positive that never gets min_hits hits never reaches the filter. The other readings
 * pass as they are. The readings with IDs then go to a CClassifyingRouter (with use_hints: a
 * track's corners are one box), whose evidence decides static or moving per corner and groups
 * the moving corners into objects. Everything else (registry, merges) is the inner router's. */
#include <dynslam/estimator/box_tracker.h>
#include <dynslam/estimator/classifying_router.h>

#include <array>
#include <limits>
#include <map>

namespace dynslam::estimator
{
class CBoxRouter : public IMeasurementRouter
{
public:
	/** The first corner ID; non-box readings with IDs from here on are rejected. */
	static constexpr int32_t kFirstCornerId = 500'000'000;
	/** The ID of corner c (0..3: front-left, front-right, rear-right, rear-left in the track's
	 * frame) of box track `track`; throws std::out_of_range beyond the ID space. */
	static int32_t cornerId(int32_t track, int corner);
	/** The four corner IDs of a track. */
	static std::array<int32_t, 4> cornerIds(int32_t track);

	/** classify.use_hints is set (the track is the corners' hint). Throws
	 * std::invalid_argument on invalid parameters. */
	CBoxRouter(const TBoxTrackerParams& tracker, TClassifyParams classify);

	std::string name() const override { return "boxes"; }
	void validate(const std::vector<TReading>& readings, const std::string& who) const override;
	void setStaticAssociation(StaticAssociationFn f) override;
	void setContext(const TRouterContext& ctx) override;
	/** Throws std::runtime_error for a step with boxes but no time stamp, a corner whose group
	 * is not a box of the step, or a box without its four corners. */
	TRoutedStep route(int step, const std::vector<TReading>& readings,
	                  const std::function<bool(int32_t)>& isKnownStatic) override;
	const CObjectRegistry& registry() const override { return m_inner.registry(); }
	CObjectRegistry& registry() override { return m_inner.registry(); }
	int32_t featureId(int32_t object, int32_t feature) const override;
	void reset() override;
	void mergeObjects(int32_t from, int32_t into) override;
	bool allowsMerge(int32_t a, int32_t b) const override;

	/** The tracker after the last step (its tracks in the world frame). */
	const CBoxTracker* boxTracker() const override { return &m_tracker; }
	Eigen::Vector3d boxPlacementPose() const override { return m_placed; }
	const CClassifyingRouter& inner() const { return m_inner; }

private:
	/** The step's boxes in the world (the ego predicted by the step's odometry, then the
	 * sensor); boxOfGroup: group -> box index. Throws std::runtime_error for a repeated group. */
	std::vector<TWorldBox> placeBoxes(const std::vector<TBoxDetection>& boxes,
	                                  std::map<int32_t, size_t>& boxOfGroup, int step);
	TBoxTrackerParams m_trackerParams;
	CBoxTracker m_tracker;
	CClassifyingRouter m_inner;
	TRouterContext m_ctx;
	double m_lastStamp = std::numeric_limits<double>::quiet_NaN();
	Eigen::Vector3d m_placed = Eigen::Vector3d::Zero();  ///< boxPlacementPose()
};
}  // namespace dynslam::estimator
