/** CDynamicKFSLAM2D: options (TOptions) and result getters. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/backend_results.h>
#include <dynslam/config_utils.h>
#include <dynslam/ekf_steps.h>

#include <algorithm>
#include <ostream>
#include <stdexcept>

namespace dynslam
{
using estimator::BlockKind;
using estimator::TBlock;

TParseOptions CDynamicKFSLAM2D::TOptions::parseOptions() const
{
	return {measurement_model, motion_noise_from_action};
}

estimator::TDropOptions CDynamicKFSLAM2D::TOptions::dropOptions() const
{
	estimator::TDropOptions d;
	d.drop_time_t_features = drop_time_t_features;
	d.keep_last_poses = keep_last_poses;
	d.drop_static_after_unseen_steps = drop_static_after_unseen_steps;
	d.record_dropped = record_dropped;
	return d;
}

// ------------------------------------------------------------------------------------------
// Options
// ------------------------------------------------------------------------------------------
void CDynamicKFSLAM2D::TOptions::loadFromConfigFile(
	const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	using namespace dynslam::config;
	rejectUnknownKeys(
		c, s,
		{"measurement_model", "Sigma_v", "motion_noise", "Sigma_w", "initial_pose", "Sigma_0",
		 "Sigma_xi", "smoothing", "Sigma_s", "drop_time_t_features", "keep_last_poses",
		 "drop_static_after_unseen_steps", "skip_prediction_on_empty_map", "static_update",
		 "innovation_gate", "first_estimate_jacobians", "record_dropped"});
	measurement_model = readChoice(c, s, "measurement_model", {"cartesian", "range_bearing"}, 0, true) == 0
							? models::MeasurementModel::Cartesian
							: models::MeasurementModel::RangeBearing;
	Sigma_v = readCovariance(c, s, "Sigma_v", Sigma_v, 2, true);
	motion_noise_from_action = readChoice(c, s, "motion_noise", {"action", "config"}, 0) == 0;
	Sigma_w = readCovariance(c, s, "Sigma_w", Sigma_w, 3, !motion_noise_from_action);
	initial_pose = readVector(c, s, "initial_pose", initial_pose, 3);
	Sigma_0 = readCovariance(c, s, "Sigma_0", Sigma_0, 3, false, true);
	Sigma_xi = readCovariance(c, s, "Sigma_xi", Sigma_xi, 2);
	smoothing = readBool(c, s, "smoothing", smoothing);
	Sigma_s = readCovariance(c, s, "Sigma_s", Sigma_s, 3, smoothing);
	drop_time_t_features = readBool(c, s, "drop_time_t_features", drop_time_t_features);
	keep_last_poses = int(readInt(c, s, "keep_last_poses", keep_last_poses));
	drop_static_after_unseen_steps =
		int(readInt(c, s, "drop_static_after_unseen_steps", drop_static_after_unseen_steps));
	skip_prediction_on_empty_map =
		readBool(c, s, "skip_prediction_on_empty_map", skip_prediction_on_empty_map);
	sparse_static_update =
		readChoice(c, s, "static_update", {"mrpt", "sparse"}, sparse_static_update ? 1 : 0) == 1;
	innovation_gate = readNonNegative(c, s, "innovation_gate", innovation_gate);
	first_estimate_jacobians = readBool(c, s, "first_estimate_jacobians", first_estimate_jacobians);
	record_dropped = readBool(c, s, "record_dropped", record_dropped);
	try
	{
		validate();
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument("[" + s + "] " + e.what());
	}
}

void CDynamicKFSLAM2D::TOptions::validate() const
{
	if (keep_last_poses < 1)
		throw std::invalid_argument(
			"keep_last_poses = " + std::to_string(keep_last_poses) + ": must be >= 1");
	if (smoothing && keep_last_poses < 3)
		throw std::invalid_argument(
			"keep_last_poses = " + std::to_string(keep_last_poses) +
			": smoothing needs the last 3 object poses (keep_last_poses >= 3)");
	if (drop_static_after_unseen_steps < 0)
		throw std::invalid_argument(
			"drop_static_after_unseen_steps = " + std::to_string(drop_static_after_unseen_steps) +
			": must be >= 0");
	if (!initial_pose.allFinite()) throw std::invalid_argument("initial_pose: not finite");
	if (!(innovation_gate >= 0 && innovation_gate < 1))
		throw std::invalid_argument(
			"innovation_gate = " + std::to_string(innovation_gate) +
			": must be a probability in [0, 1) (0 = no gate)");
}

void CDynamicKFSLAM2D::TOptions::dumpToTextStream(std::ostream& out) const
{
	using config::formatMatrix;
	out << "\n----------- [CDynamicKFSLAM2D::TOptions] ------------\n\n";
	out << "measurement_model              = " << models::toString(measurement_model) << "\n";
	out << "Sigma_v                        = " << formatMatrix(Sigma_v) << "\n";
	out << "motion_noise                   = " << (motion_noise_from_action ? "action" : "config")
		<< "\n";
	out << "Sigma_w                        = " << formatMatrix(Sigma_w) << "\n";
	out << "initial_pose                   = " << formatMatrix(initial_pose.transpose()) << "\n";
	out << "Sigma_0                        = " << formatMatrix(Sigma_0) << "\n";
	out << "Sigma_xi                       = " << formatMatrix(Sigma_xi) << "\n";
	out << "smoothing                      = " << (smoothing ? "true" : "false") << "\n";
	out << "Sigma_s                        = " << formatMatrix(Sigma_s) << "\n";
	out << "drop_time_t_features           = " << (drop_time_t_features ? "true" : "false") << "\n";
	out << "keep_last_poses                = " << keep_last_poses << "\n";
	out << "drop_static_after_unseen_steps = " << drop_static_after_unseen_steps << "\n";
	out << "skip_prediction_on_empty_map   = " << (skip_prediction_on_empty_map ? "true" : "false")
		<< "\n";
	out << "static_update                  = " << (sparse_static_update ? "sparse" : "mrpt") << "\n";
	out << "innovation_gate                = " << innovation_gate << "\n";
	out << "first_estimate_jacobians       = " << (first_estimate_jacobians ? "true" : "false")
		<< "\n";
	out << "record_dropped                 = " << (record_dropped ? "true" : "false") << "\n";
}

// ------------------------------------------------------------------------------------------
// Results
// ------------------------------------------------------------------------------------------
mrpt::poses::CPosePDFGaussian CDynamicKFSLAM2D::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	p.mean = mrpt::poses::CPose2D(m_xkk[0], m_xkk[1], m_xkk[2]);
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) p.cov(i, j) = m_pkk(i, j);
	return p;
}

std::vector<TStaticLandmarkEstimate> CDynamicKFSLAM2D::getStaticLandmarks(bool includeDropped) const
{
	std::vector<TStaticLandmarkEstimate> out;
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		if (m_layout[b].kind != BlockKind::StaticLandmark) continue;
		const int k = m_layout.first(b);
		TStaticLandmarkEstimate e;
		e.id = m_layout[b].id;
		e.mean = Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]);
		e.cov << m_pkk(k, k), m_pkk(k, k + 1), m_pkk(k + 1, k), m_pkk(k + 1, k + 1);
		e.in_state = true;
		out.push_back(e);
	}
	if (includeDropped) out.insert(out.end(), m_droppedStatic.begin(), m_droppedStatic.end());
	return out;
}

std::vector<TObjectFeatureEstimate> CDynamicKFSLAM2D::getObjectFeatures() const
{
	std::vector<TObjectFeatureEstimate> out;
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		const TBlock& t = m_layout[b];
		if (t.kind != BlockKind::ObjectFeature0 && t.kind != BlockKind::ObjectFeatureT) continue;
		const int k = m_layout.first(b);
		TObjectFeatureEstimate e;
		e.object = t.object;
		e.feature = t.feature;
		e.id = t.id;
		e.at_time0 = t.kind == BlockKind::ObjectFeature0;
		e.step = t.step;
		e.mean = Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]);
		e.cov << m_pkk(k, k), m_pkk(k, k + 1), m_pkk(k + 1, k), m_pkk(k + 1, k + 1);
		out.push_back(e);
	}
	return out;
}

std::map<int32_t, TObjectTrack> CDynamicKFSLAM2D::getObjectTracks() const
{
	std::map<int32_t, TObjectTrack> out = tracksFromRegistry(m_router->registry());
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		const TBlock& t = m_layout[b];
		if (t.kind != BlockKind::ObjectPose) continue;
		const std::vector<int> idx = m_layout.indices(b);
		TObjectPoseEstimate e;
		e.step = t.step;
		e.mean = m_xkk.asEigen()(idx);
		e.cov = ekf::marginal(m_pkk.asEigen(), idx);
		e.in_state = true;
		out[t.object].poses.push_back(e);
	}
	sortTrackPoses(out);
	return out;
}

std::vector<size_t> CDynamicKFSLAM2D::padIndices() const
{
	const std::vector<int> p = m_layout.padIndices();
	return std::vector<size_t>(p.begin(), p.end());
}

void CDynamicKFSLAM2D::onLayoutChanged()
{
	m_slots.clear();
	m_staticBlock.clear();
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		const TBlock& t = m_layout[b];
		TSlot s;
		s.id = t.id;
		s.object = t.object;
		s.feature = t.feature;
		s.step = t.step;
		switch (t.kind)
		{
			case BlockKind::StaticLandmark:
				s.kind = SlotKind::StaticLandmark;
				m_staticBlock[t.id] = b;
				break;
			case BlockKind::ObjectFeature0:
				s.kind = SlotKind::ObjectFeature0;
				break;
			case BlockKind::ObjectFeatureT:
				s.kind = SlotKind::ObjectFeatureT;
				break;
			case BlockKind::ObjectPose:
				s.kind = SlotKind::ObjectPoseA;
				s.id = -1;
				break;
			case BlockKind::ObjectVelocity:
				throw std::logic_error("CDynamicKFSLAM2D: object velocities are not in this filter");
		}
		m_slots.push_back(s);
		if (t.kind == BlockKind::ObjectPose && t.dim == 3)
		{
			s.kind = SlotKind::ObjectPoseB;  // [dtheta, pad]
			m_slots.push_back(s);
		}
	}
}

namespace
{
void appendLabels(const TBlock& t, std::vector<std::string>& labels)
{
	const std::string o = "obj" + std::to_string(t.object);
	switch (t.kind)
	{
		case BlockKind::StaticLandmark:
			labels.push_back("lm" + std::to_string(t.id) + ".x");
			labels.push_back("lm" + std::to_string(t.id) + ".y");
			break;
		case BlockKind::ObjectFeature0:
		case BlockKind::ObjectFeatureT:
		{
			const bool t0 = t.kind == BlockKind::ObjectFeature0;
			const std::string f = o + ".f" + std::to_string(t.feature) +
								  (t0 ? ".t0" : ".t" + std::to_string(t.step));
			labels.push_back(f + ".x");
			labels.push_back(f + ".y");
			break;
		}
		case BlockKind::ObjectPose:
		{
			const std::string p = o + ".xi" + std::to_string(t.step);
			labels.push_back(p + ".dx");
			labels.push_back(p + ".dy");
			if (t.dim == 3) labels.push_back(p + ".dtheta");
			break;
		}
		case BlockKind::ObjectVelocity:
			for (int i = 0; i < t.dim; ++i)
				labels.push_back(o + ".v" + std::to_string(t.step) + "." + std::to_string(i));
			break;
	}
}
}  // namespace

void CDynamicKFSLAM2D::getStateWithoutPads(
	Eigen::VectorXd& x, Eigen::MatrixXd& P, std::vector<std::string>* labels) const
{
	const std::vector<int> keep = ekf::keptIndices(int(m_xkk.size()), m_layout.padIndices());
	x = m_xkk.asEigen()(keep);
	P = m_pkk.asEigen()(keep, keep);
	if (!labels) return;
	labels->assign({"ego.x", "ego.y", "ego.theta"});
	for (const TBlock& t : m_layout.blocks()) appendLabels(t, *labels);
}
}  // namespace dynslam
