#include <dynslam/apps/CStaticBaselineBackend.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/estimator/unknown_id_association.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <algorithm>
#include <cmath>
#include <limits>
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
	m_keys.clear();
	m_idOfKey.clear();
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
	// A copy with MRPT's keys; the caller's data stay untouched (other filters use them too).
	const auto input = mrptInput(*obs);
	const size_t readings = input->sensedData.size();
	mrpt::obs::CSensoryFrame::Ptr sf = mrpt::obs::CSensoryFrame::Create();
	sf->insert(input);
	m_filter->processActionObservation(act, sf);

	const int step = m_report.step + 1;
	m_report = TStepReport();
	m_report.step = step;
	m_report.static_new = m_filter->getLastDataAssociation().newly_inserted_landmarks.size();
	m_report.static_updates = readings >= m_report.static_new ? readings - m_report.static_new : 0;
	for (const auto& m : input->sensedData)
		if (m.landmarkID < 0) ++m_report.unknown_id_associated;
	const size_t unknownNew = [&]
	{
		size_t n = 0;
		for (const auto& [obsIdx, idx] :
		     m_filter->getLastDataAssociation().newly_inserted_landmarks)
			n += input->sensedData.at(obsIdx).landmarkID < 0;
		return n;
	}();
	m_report.unknown_id_new = unknownNew;
	m_report.unknown_id_associated -= unknownNew;
}

std::shared_ptr<mrpt::obs::CObservationBearingRange> CStaticBaselineBackend::mrptInput(
    const mrpt::obs::CObservationBearingRange& obs)
{
	auto out = std::make_shared<mrpt::obs::CObservationBearingRange>(obs);
	out->sensedData.clear();
	for (auto m : obs.sensedData)
	{
		if (m_mode == Mode::StaticOnly && m.landmarkID >= 0 && !ids::isStatic(m.landmarkID))
		{
			++m_removed;
			continue;
		}
		if (m.landmarkID >= 0) m.landmarkID = keyOf(m.landmarkID);
		out->sensedData.push_back(m);
	}
	// The -1 readings first: MRPT 2.5.8 writes the association of the k-th -1 reading into row
	// k of the whole observation (CRangeBearingKFSLAM2D::OnGetObservationsAndDataAssociation,
	// data_association[it->first] with it->first the row among the -1 readings), which is that
	// reading's row only if the -1 readings come first.
	std::stable_partition(out->sensedData.begin(), out->sensedData.end(),
	                      [](const auto& m) { return m.landmarkID < 0; });
	return out;
}

int32_t CStaticBaselineBackend::keyOf(int32_t id)
{
	const auto [it, added] = m_keys.try_emplace(id, 0);
	if (added)
	{
		it->second = std::numeric_limits<int32_t>::max() - int32_t(m_idOfKey.size());
		m_idOfKey.push_back(id);
	}
	return it->second;
}

int32_t CStaticBaselineBackend::idOfKey(int64_t key) const
{
	const int64_t k = int64_t(std::numeric_limits<int32_t>::max()) - key;
	if (k >= 0 && k < int64_t(m_idOfKey.size())) return m_idOfKey[size_t(k)];
	return estimator::kFirstResolvedId + int32_t(key);  // a landmark started by a -1 reading
}

mrpt::poses::CPosePDFGaussian CStaticBaselineBackend::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	m_filter->getCurrentRobotPose(p);
	return p;
}

std::vector<TStaticLandmarkEstimate> CStaticBaselineBackend::getStaticLandmarks() const
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
		e.id = it == ids.end() ? -1 : idOfKey(int64_t(it->second));
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
