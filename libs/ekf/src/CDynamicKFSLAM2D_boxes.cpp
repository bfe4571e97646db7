/** feature_labels = boxes (issue 31, doc/boxes.md): what the EKF gives the box router (the
 * joint prediction of a box whose corners are static landmarks of the state) and the tracks it
 * reports (trackedBoxes: a parked car held as four landmarks at the map's centre, every other
 * box as the tracker has it, relative to the pose that placed it). A moving object's pose in
 * the filter is that of its founders' centroid, the box centre only when all four corners
 * founded it: measured worse on 0000-0010 (doc/boxes.md), so it is not used. */
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/box_router.h>

namespace dynslam
{
bool CDynamicKFSLAM2D::boxPrediction(const std::array<int32_t, 4>& ids, Eigen::Vector2d& c,
                                     Eigen::Matrix2d& C) const
{
	std::array<Eigen::Index, 4> k{};
	for (size_t i = 0; i < 4; ++i)
	{
		const auto it = m_staticBlock.find(ids[i]);
		if (it == m_staticBlock.end()) return false;
		k[i] = m_layout.first(it->second);
	}
	// The footprint centre is the mean of the four corners: c = A m, C = A P A^T with
	// A = [I/4 I/4 I/4 I/4] on the corners' blocks.
	const auto P = cov();
	c.setZero();
	C.setZero();
	for (size_t i = 0; i < 4; ++i)
	{
		c += 0.25 * Eigen::Vector2d(m_xkk[size_t(k[i])], m_xkk[size_t(k[i]) + 1]);
		for (size_t j = 0; j < 4; ++j) C += P.block(k[i], k[j], 2, 2) / 16.0;
	}
	return true;
}

std::vector<TTrackedBox> CDynamicKFSLAM2D::trackedBoxes() const
{
	const estimator::CBoxTracker* tracker = m_router ? m_router->boxTracker() : nullptr;
	if (!tracker) return {};
	const Eigen::Vector3d ego(m_xkk[0], m_xkk[1], m_xkk[2]);
	const Eigen::Vector3d placed = m_router->boxPlacementPose();
	std::vector<TTrackedBox> out;
	for (const estimator::TBoxTrack& t : tracker->tracks())
	{
		if (!options.boxes.reports(t, m_step + 1)) continue;  // tracker_baseline's output rule
		TTrackedBox b;
		b.track = t.id;
		b.cls = t.cls;
		b.score = t.score;
		// The tracker's box, relative to the pose that placed this step's boxes.
		b.pose = models::poseDifference(t.x.head<3>(), placed);
		// A box mapped as four static landmarks: the map's centre (after this step's update),
		// relative to the ego updated with it.
		Eigen::Vector2d c;
		Eigen::Matrix2d C;
		if (boxPrediction(estimator::CBoxRouter::cornerIds(t.id), c, C))
			b.pose = models::poseDifference(Eigen::Vector3d(c.x(), c.y(), t.x(2)), ego);
		b.extent = t.x.segment<2>(3);
		out.push_back(b);
	}
	return out;
}
}  // namespace dynslam
