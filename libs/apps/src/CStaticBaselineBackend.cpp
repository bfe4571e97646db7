#include <dynslam/apps/CStaticBaselineBackend.h>
#include <dynslam/config_utils.h>
#include <dynslam/landmark_ids.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <cmath>
#include <ostream>
#include <stdexcept>

namespace dynslam::apps
{
CStaticBaselineBackend::CStaticBaselineBackend(Mode mode)
    : m_mode(mode), m_filter(std::make_unique<mrpt::slam::CRangeBearingKFSLAM2D>())
{
}
CStaticBaselineBackend::~CStaticBaselineBackend() = default;

std::string CStaticBaselineBackend::name() const
{
	return m_mode == Mode::AllFeatures ? "static_all" : "static_landmarks_only";
}

void CStaticBaselineBackend::loadOptions(const mrpt::config::CConfigFileBase& ini,
                                         const std::string& section)
{
	using namespace dynslam::config;
	// MRPT reads these leniently; R must not silently fall back to MRPT's defaults.
	readPositive(ini, section, "std_sensor_range", 0, true);
	readPositive(ini, section, "std_sensor_yaw_deg", 0, true);
	const std::string kf = section + "_KalmanFilter";
	if (has(ini, kf, "method"))  // MRPT's kfIKF throws, kfIKFFull does not re-linearise
		readChoice(ini, kf, "method", {"kfEKFNaive", "kfEKFAlaDavison", "0", "1"}, 0, false);
	if (section == "RangeBearingKFSLAM")
		m_filter->loadOptions(ini);
	else
	{
		m_filter->options.loadFromConfigFile(ini, section);
		m_filter->KF_options.loadFromConfigFile(ini, kf);
	}
	if (!(m_filter->options.std_sensor_range > 0) || !(m_filter->options.std_sensor_yaw > 0))
		fail(section, "std_sensor_range / std_sensor_yaw_deg", "", "must be positive");
	m_filter->reset();
	m_report = TStepReport();
	m_removed = 0;
	m_seenId = m_seenUnknown = false;
}

void CStaticBaselineBackend::dumpOptions(std::ostream& out) const
{
	m_filter->options.dumpToTextStream(out);
	m_filter->KF_options.dumpToTextStream(out);
	out << "input_mode = "
	    << (m_mode == Mode::AllFeatures ? "all features" : "static landmarks only") << "\n";
}

void CStaticBaselineBackend::processActionObservation(
    const mrpt::obs::CActionCollection::Ptr& action, const mrpt::obs::CSensoryFrame::Ptr& SF)
{
	if (!action) throw std::runtime_error(name() + ": null action collection");
	if (!SF) throw std::runtime_error(name() + ": null sensory frame");
	auto obs = SF->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	if (!obs)
		throw std::runtime_error(name() + ": the sensory frame holds no CObservationBearingRange");

	mrpt::obs::CActionCollection::Ptr act = action;
	mrpt::obs::CSensoryFrame::Ptr sf = SF;
	size_t readings = obs->sensedData.size();
	if (m_mode == Mode::StaticOnly)
	{
		// A filtered copy; the caller's data stay untouched (other filters use them too).
		auto filtered = std::make_shared<mrpt::obs::CObservationBearingRange>(*obs);
		filtered->sensedData.clear();
		for (const auto& m : obs->sensedData)
			if (ids::isStatic(m.landmarkID))
				filtered->sensedData.push_back(m);
			else
				++m_removed;
		readings = filtered->sensedData.size();
		sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(filtered);
	}
	else
		checkIdsNotMixed(*obs, m_report.step + 1);
	m_filter->processActionObservation(act, sf);

	const int step = m_report.step + 1;
	m_report = TStepReport();
	m_report.step = step;
	m_report.static_new = m_filter->getLastDataAssociation().newly_inserted_landmarks.size();
	m_report.static_updates = readings >= m_report.static_new ? readings - m_report.static_new : 0;
}

void CStaticBaselineBackend::checkIdsNotMixed(const mrpt::obs::CObservationBearingRange& obs,
                                              int step)
{
	// MRPT's CRangeBearingKFSLAM2D keeps a bimap landmark ID <-> index: a second new landmark
	// with ID -1 (association unknown, e.g. clutter) next to labelled readings throws
	// "Duplicated `key` with different `value`" from deep inside MRPT. Say which reading.
	for (size_t i = 0; i < obs.sensedData.size(); ++i)
	{
		const bool unknown = obs.sensedData[i].landmarkID < 0;
		(unknown ? m_seenUnknown : m_seenId) = true;
		if (m_seenUnknown && m_seenId)
			throw std::runtime_error(
			    name() + ": step " + std::to_string(step) + ": measurement " + std::to_string(i) +
			    " (landmark ID " + std::to_string(obs.sensedData[i].landmarkID) +
			    "): the rawlog mixes landmark IDs with -1 (association unknown), which MRPT's "
			    "CRangeBearingKFSLAM2D does not support");
	}
}

mrpt::poses::CPosePDFGaussian CStaticBaselineBackend::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	m_filter->getCurrentRobotPose(p);
	return p;
}

std::vector<TStaticLandmarkEstimate> CStaticBaselineBackend::getStaticLandmarks(bool) const
{
	mrpt::poses::CPosePDFGaussian pose;
	std::vector<mrpt::math::TPoint2D> lms;
	std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
	mrpt::math::CVectorDouble x;
	mrpt::math::CMatrixDouble P;
	m_filter->getCurrentState(pose, lms, ids, x, P);
	std::vector<TStaticLandmarkEstimate> out;
	out.reserve(lms.size());
	for (size_t i = 0; i < lms.size(); ++i)
	{
		TStaticLandmarkEstimate e;
		const auto it = ids.find(static_cast<unsigned int>(i));
		e.id = it == ids.end() ? -1 : static_cast<int32_t>(it->second);
		e.mean = Eigen::Vector2d(lms[i].x, lms[i].y);
		const size_t k = 3 + 2 * i;
		e.cov << P(k, k), P(k, k + 1), P(k + 1, k), P(k + 1, k + 1);
		e.in_state = true;
		out.push_back(e);
	}
	return out;
}

Eigen::MatrixXd CStaticBaselineBackend::landmarksJointCov() const
{
	const auto& P = const_cast<mrpt::slam::CRangeBearingKFSLAM2D&>(*m_filter).internal_getPkk();
	const Eigen::Index n = P.rows() - 3;
	if (n <= 0) return {};
	return P.asEigen().block(3, 3, n, n);
}
}  // namespace dynslam::apps
