#pragma once
/** @file CStaticBaselineBackend.h
 * MRPT's static EKF-SLAM, mrpt::slam::CRangeBearingKFSLAM2D, unchanged, behind the project's
 * ISlamBackend interface, in one of two input modes:
 *  - AllFeatures (filter name "static_all"): every range-bearing reading goes to the filter,
 *    so the features of moving objects are taken for static landmarks (the naive baseline);
 *  - StaticOnly ("static_landmarks_only"): readings whose landmark ID is an object feature
 *    (dynslam/landmark_ids.h) are removed before the filter sees them (an oracle baseline
 *    that knows which features move).
 *
 * Configuration: MRPT's own sections [RangeBearingKFSLAM] and [RangeBearingKFSLAM_KalmanFilter]
 * (read by CRangeBearingKFSLAM2D::loadOptions). MRPT reads them leniently (defaults for
 * missing keys); this wrapper additionally requires std_sensor_range and std_sensor_yaw_deg
 * (they set R) and rejects non-positive values and unsupported KF methods. */
#include <dynslam/ISlamBackend.h>
#include <mrpt/config/CConfigFileBase.h>

#include <memory>
#include <string>

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
	std::vector<TStaticLandmarkEstimate> getStaticLandmarks(
	    bool includeDropped = true) const override;
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
	/** Mode AllFeatures: throws naming the reading once -1 IDs and IDs >= 0 have both come. */
	void checkIdsNotMixed(const mrpt::obs::CObservationBearingRange& obs, int step);

	Mode m_mode;
	std::unique_ptr<mrpt::slam::CRangeBearingKFSLAM2D> m_filter;
	TStepReport m_report;
	size_t m_removed = 0;
	bool m_seenId = false, m_seenUnknown = false;  ///< IDs >= 0 / -1 seen (mode AllFeatures)
};
}  // namespace dynslam::apps
