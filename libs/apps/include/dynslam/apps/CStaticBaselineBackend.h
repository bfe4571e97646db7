#pragma once
/** @file CStaticBaselineBackend.h
 * MRPT's static EKF-SLAM, mrpt::slam::CRangeBearingKFSLAM2D, unchanged, behind the project's
 * ISlamBackend interface, in one of two input modes:
 *  - AllFeatures (filter name "static_all"): every range-bearing reading goes to the filter,
 *    so the features of moving objects are taken for static landmarks (the naive baseline);
 *  - StaticOnly ("static_landmarks_only"): readings whose landmark ID is an object feature
 *    (dynslam/core/landmark_ids.h) are removed before the filter sees them (an oracle baseline
 *    that knows which features move).
 * Readings with MRPT's unknown landmark ID -1 go to the filter in both modes, which associates
 * them as MRPT does (data_assoc_* keys of [RangeBearingKFSLAM]); IDs may be mixed with -1.
 *
 * Configuration: MRPT's own sections [RangeBearingKFSLAM] and [RangeBearingKFSLAM_KalmanFilter]
 * (read by CRangeBearingKFSLAM2D::loadOptions). MRPT reads them leniently (defaults for
 * missing keys); this wrapper additionally requires std_sensor_range and std_sensor_yaw_deg
 * (they set R) and rejects non-positive values and unsupported KF methods. */
#include <dynslam/common/ISlamBackend.h>
#include <mrpt/config/CConfigFileBase.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mrpt::obs
{
class CObservationBearingRange;
}
namespace mrpt::slam
{
class CRangeBearingKFSLAM2D;
}

namespace dynslam::apps
{
class CStaticBaselineBackend : public ISlamBackend
{
public:
	enum class Mode
	{
		AllFeatures,
		StaticOnly
	};
	explicit CStaticBaselineBackend(Mode mode);
	~CStaticBaselineBackend() override;

	/** Loads [section] and [section_KalmanFilter] (MRPT's keys) and resets the filter. Throws
	 * std::invalid_argument naming section and key on missing or invalid R values. */
	void loadOptions(const mrpt::config::CConfigFileBase& ini,
	                 const std::string& section = "RangeBearingKFSLAM");
	/** The effective options of the wrapped filter (both sections). */
	void dumpOptions(std::ostream& out) const;

	std::string name() const override;
	void processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
	                              const mrpt::obs::CSensoryFrame::Ptr& SF) override;
	mrpt::poses::CPosePDFGaussian getEgoPose() const override;
	/** Every landmark of the filter's map, moving features included (mode AllFeatures). */
	std::vector<TStaticLandmarkEstimate> getStaticLandmarks() const override;
	/** MRPT's filter never drops a landmark: empty. */
	std::vector<TStaticLandmarkEstimate> getDroppedStaticLandmarks() const override { return {}; }
	std::vector<TObjectFeatureEstimate> getObjectFeatures() const override { return {}; }
	std::map<int32_t, TObjectTrack> getObjectTracks() const override { return {}; }
	const TStepReport& getLastStepReport() const override { return m_report; }
	/** Joint covariance of the landmarks in the order of getStaticLandmarks(). */
	Eigen::MatrixXd landmarksJointCov() const;

	Mode mode() const { return m_mode; }
	/** Readings removed so far (mode StaticOnly). */
	size_t removedReadings() const { return m_removed; }
	mrpt::slam::CRangeBearingKFSLAM2D& filter() { return *m_filter; }

private:
	/** The observation handed to MRPT: each ID >= 0 replaced by its key (keyOf), -1 kept (MRPT
	 * associates it) and put first (MRPT 2.5.8 writes the association of the k-th -1 reading
	 * into row k); mode StaticOnly: object features removed. */
	std::shared_ptr<mrpt::obs::CObservationBearingRange> mrptInput(
	    const mrpt::obs::CObservationBearingRange& obs);
	/** MRPT's CRangeBearingKFSLAM2D keys a landmark started by a -1 reading by its map index
	 * (OnNewLandmarkAddedToMap) in the same ID <-> index bimap as the given IDs, so a given ID
	 * equal to a later index throws "Duplicated `key`" from inside MRPT. Given IDs are therefore
	 * handed to MRPT as keys from INT32_MAX down (INT32_MAX - n for the n-th distinct ID), which
	 * no map index reaches; the association by ID is unchanged. */
	int32_t keyOf(int32_t id);
	/** The ID of MRPT key `key`: a given ID, or kFirstResolvedId + index for a -1 landmark. */
	int32_t idOfKey(int64_t key) const;

	Mode m_mode;
	std::unique_ptr<mrpt::slam::CRangeBearingKFSLAM2D> m_filter;
	TStepReport m_report;
	size_t m_removed = 0;
	std::map<int32_t, int32_t> m_keys;  ///< given ID -> MRPT key (keyOf)
	std::vector<int32_t> m_idOfKey;     ///< INT32_MAX - key -> given ID
};
}  // namespace dynslam::apps
