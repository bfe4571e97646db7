/** CDynamicKFSLAM2D: input parsing, the MRPT Kalman-filter hooks (prediction, static update,
 * static augmentation in MRPT's path) and the step driver. Augmentations, drops and object
 * steps: CDynamicKFSLAM2D_objects.cpp. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/ekf_steps.h>
#include <dynslam/landmark_ids.h>
#include <dynslam/models/se2.h>

#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/system/string_utils.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace dynslam
{
const char* toString(SlotKind k)
{
	switch (k)
	{
		case SlotKind::StaticLandmark:
			return "static_landmark";
		case SlotKind::ObjectFeature0:
			return "object_feature_t0";
		case SlotKind::ObjectFeatureT:
			return "object_feature_t";
		case SlotKind::ObjectPoseA:
			return "object_pose_a";
		case SlotKind::ObjectPoseB:
			return "object_pose_b";
	}
	return "?";
}

CDynamicKFSLAM2D::CDynamicKFSLAM2D()
{
	setLoggerName("CDynamicKFSLAM2D");
	reset();
}

void CDynamicKFSLAM2D::reset()
{
	m_xkk.resize(3);
	for (int i = 0; i < 3; ++i) m_xkk[i] = options.initial_pose[i];
	m_pkk.setSize(3, 3);
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) m_pkk(i, j) = options.Sigma_0(i, j);
	m_slots.clear();
	m_staticSlot.clear();
	m_staticLastSeen.clear();
	m_droppedStatic.clear();
	m_objects.clear();
	m_static.clear();
	m_objectMeas.clear();
	m_step = -1;
	m_report = TStepReport();
	m_failed = false;
	m_firstEstimate.clear();
	m_predictedEgo.reset();
}

void CDynamicKFSLAM2D::loadOptions(const mrpt::config::CConfigFileBase& ini, const std::string& section)
{
	options.loadFromConfigFile(ini, section);
	// Check `method` before MRPT parses it: MRPT's read_enum casts any value that starts with a
	// digit to TKFMethod without a range check (undefined behaviour for e.g. "5"; found by
	// fuzzing under UBSan).
	const std::string kf = section + "_KalmanFilter";
	const std::string method = mrpt::system::trim(ini.read_string(kf, "method", "kfEKFNaive"));
	if (method != "kfEKFNaive" && method != "kfEKFAlaDavison" && method != "0" && method != "1")
		throw std::invalid_argument(
			"[" + kf + "] method = " + method +
			": only kfEKFNaive and kfEKFAlaDavison are supported (MRPT's kfIKF is not "
			"implemented and kfIKFFull does not re-linearise)");
	KF_options.loadFromConfigFile(ini, kf);
	reset();
}

// ------------------------------------------------------------------------------------------
// Input
// ------------------------------------------------------------------------------------------
void CDynamicKFSLAM2D::validateAndParse(
	const mrpt::obs::CActionCollection::Ptr& action, const mrpt::obs::CSensoryFrame::Ptr& SF)
{
	using namespace std::string_literals;
	if (!action) throw std::runtime_error("CDynamicKFSLAM2D: null action collection");
	const auto mov = action->getBestMovementEstimation();
	if (!mov)
		throw std::runtime_error(
			"CDynamicKFSLAM2D: the action collection holds no CActionRobotMovement2D (" +
			std::to_string(action->size()) + " action(s) of another type)");
	mrpt::poses::CPosePDFGaussian inc(*mov->poseChange);
	const Eigen::Vector3d u(inc.mean.x(), inc.mean.y(), inc.mean.phi());
	const Eigen::Matrix3d U = inc.cov.asEigen();
	if (!u.allFinite() || !U.allFinite())
		throw std::runtime_error("CDynamicKFSLAM2D: odometry increment or covariance not finite");
	if (options.motion_noise_from_action)
	{
		const Eigen::Matrix3d Us = 0.5 * (U + U.transpose());
		if ((U - Us).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, U.cwiseAbs().maxCoeff()) ||
			Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Us).eigenvalues().minCoeff() <
				-1e-12 * std::max(1.0, U.norm()))
			throw std::runtime_error(
				"CDynamicKFSLAM2D: odometry covariance is not symmetric positive semi-definite");
	}

	std::vector<TMeas> stat, objs;
	double maxRange = 0;
	if (!SF) throw std::runtime_error("CDynamicKFSLAM2D: null sensory frame");
	const auto obs = SF->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	if (obs)
	{
		const auto& sp = obs->sensorLocationOnRobot;
		if (std::abs(sp.x()) + std::abs(sp.y()) + std::abs(sp.z()) + std::abs(sp.yaw()) +
				std::abs(sp.pitch()) + std::abs(sp.roll()) >
			0)
			throw std::runtime_error(
				"CDynamicKFSLAM2D: sensorLocationOnRobot must be the identity (the models place "
				"the sensor at the robot's origin)");
		maxRange = obs->maxSensorDistance;
		std::set<int32_t> seen;
		for (size_t i = 0; i < obs->sensedData.size(); ++i)
		{
			const auto& m = obs->sensedData[i];
			const std::string where = "measurement " + std::to_string(i) + " (landmark ID " +
									  std::to_string(m.landmarkID) + ")";
			if (!std::isfinite(m.range) || !std::isfinite(m.yaw) || !std::isfinite(m.pitch))
				throw std::runtime_error("CDynamicKFSLAM2D: NaN or Inf in " + where);
			if (m.pitch != 0)
				throw std::runtime_error("CDynamicKFSLAM2D: non-zero pitch in " + where + " (2-D SLAM)");
			if (!(m.range >= 0)) throw std::runtime_error("CDynamicKFSLAM2D: negative range in " + where);
			if (options.measurement_model == models::MeasurementModel::RangeBearing && m.range == 0)
				throw std::runtime_error(
					"CDynamicKFSLAM2D: zero range in " + where + " (bearing undefined)");
			const auto kind = ids::classify(m.landmarkID);
			if (kind == ids::IdKind::Invalid)
				throw std::runtime_error(
					"CDynamicKFSLAM2D: " + where +
					" is in no known ID range (static 0..99999, object features >= 100000; "
					"see dynslam/landmark_ids.h)");
			if (!seen.insert(m.landmarkID).second)
				throw std::runtime_error("CDynamicKFSLAM2D: duplicate " + where);
			const TMeas tm{
				m.landmarkID, models::fromRangeBearing(options.measurement_model, m.range, m.yaw)};
			(kind == ids::IdKind::Static ? stat : objs).push_back(tm);
		}
	}
	// Everything validated: commit the inputs.
	m_odoIncrement = mrpt::poses::CPose2D(u[0], u[1], u[2]);
	m_odoCov = U;
	m_static.swap(stat);
	m_objectMeas.swap(objs);
	m_maxRange = maxRange;
}

void CDynamicKFSLAM2D::processActionObservation(
	const mrpt::obs::CActionCollection::Ptr& action, const mrpt::obs::CSensoryFrame::Ptr& SF)
{
	if (m_failed)
		throw std::runtime_error(
			"CDynamicKFSLAM2D: an earlier step failed numerically; call reset() before going on");
	validateAndParse(action, SF);
	++m_step;
	m_report = TStepReport();
	m_report.step = m_step;
	try
	{
		// 1. MRPT: prediction (Alg. 7), static update (Alg. 5), static augmentation (Alg. 3)
		runOneKalmanIteration();
		for (const auto& m : m_static) m_staticLastSeen[m.id] = m_step;

		// 2-5. New entries, object steps and drops, committed together (one covariance rewrite;
		// two with smoothing, which needs the new poses in the state before the drops).
		TPending plan;
		planFeatures(plan);  // Alg. 3 (new static landmarks in the sparse path; objects)
		planObjectPoses(plan);  // Alg. 4
		if (options.smoothing)
		{
			commit(plan);
			applySmoothing();  // Alg. 6
		}
		planDrops(plan);
		commit(plan);
		recordFirstEstimates();  // first-estimate Jacobians (optional)
	}
	catch (const std::exception& e)
	{
		// A numerical failure inside a step (e.g. an innovation covariance that is not positive
		// definite with extreme noise settings) leaves the state half-updated: never go on
		// silently from there.
		m_failed = true;
		throw std::runtime_error(
			"CDynamicKFSLAM2D: step " + std::to_string(m_step) +
			" failed, the filter must be reset(): " + std::string(e.what()));
	}
}

// ------------------------------------------------------------------------------------------
// MRPT hooks
// ------------------------------------------------------------------------------------------
void CDynamicKFSLAM2D::OnGetAction(KFArray_ACT& u) const
{
	u[0] = m_odoIncrement.x();
	u[1] = m_odoIncrement.y();
	u[2] = m_odoIncrement.phi();
}

void CDynamicKFSLAM2D::OnTransitionModel(
	const KFArray_ACT& u, KFArray_VEH& xv, bool& out_skipPrediction) const
{
	if (options.skip_prediction_on_empty_map && m_xkk.size() == 3)
	{
		out_skipPrediction = true;
		return;
	}
	const Eigen::Vector3d out = models::composePose(
		Eigen::Vector3d(xv[0], xv[1], xv[2]), Eigen::Vector3d(u[0], u[1], u[2]));
	for (int i = 0; i < 3; ++i) xv[i] = out[i];
}

void CDynamicKFSLAM2D::OnTransitionJacobian(KFMatrix_VxV& F) const
{
	Eigen::Matrix3d J_out_x;
	const Eigen::Vector3d next = models::composePose(
		Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]),
		Eigen::Vector3d(m_odoIncrement.x(), m_odoIncrement.y(), m_odoIncrement.phi()), &J_out_x);
	if (options.first_estimate_jacobians && m_predictedEgo)
	{
		// FEJ: the heading column from the first estimates of the ego positions,
		// p_{k+1|k} - p_{k|k-1}, instead of p_{k+1|k} - p_{k|k} = R(theta_{k|k}) u. First step:
		// no earlier prediction, the standard Jacobian (then p_{k|k} is the prior).
		J_out_x(0, 2) = -(next[1] - (*m_predictedEgo)[1]);
		J_out_x(1, 2) = next[0] - (*m_predictedEgo)[0];
	}
	F = J_out_x;
}

void CDynamicKFSLAM2D::OnTransitionNoise(KFMatrix_VxV& Q) const
{
	// Noise on the robot-frame increment, mapped by J_out_u = blkdiag(R(theta), 1): this is
	// CPosePDFGaussian::rotateCov(theta), as in CRangeBearingKFSLAM2D.
	Eigen::Matrix3d J_out_u;
	models::composePose(
		Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]), Eigen::Vector3d::Zero(), nullptr, &J_out_u);
	const Eigen::Matrix3d& S = options.motion_noise_from_action ? m_odoCov : options.Sigma_w;
	Q = J_out_u * S * J_out_u.transpose();
}

void CDynamicKFSLAM2D::OnGetObservationNoise(KFMatrix_OxO& R) const { R = options.Sigma_v; }

void CDynamicKFSLAM2D::OnPreComputingPredictions(
	const vector_KFArray_OBS&, std::vector<size_t>& out_idx) const
{
	// IDs are known: predict exactly the tracked static landmarks seen in this step (none when
	// the sparse update path does the update itself).
	out_idx.clear();
	if (options.sparse_static_update) return;
	for (const auto& m : m_static)
	{
		const auto it = m_staticSlot.find(m.id);
		if (it != m_staticSlot.end()) out_idx.push_back(it->second);
	}
}

namespace
{
/** h() that never throws (MRPT predicts every slot, including non-observed ones). */
Eigen::Vector2d safeObserve(
	models::MeasurementModel model, const Eigen::Vector3d& x, const Eigen::Vector2d& f)
{
	if (model == models::MeasurementModel::RangeBearing && (f - x.head<2>()).squaredNorm() == 0)
		return Eigen::Vector2d::Zero();
	return models::observe(model, x, f);
}
}  // namespace

void CDynamicKFSLAM2D::OnObservationModel(
	const std::vector<size_t>& idx, vector_KFArray_OBS& out) const
{
	const Eigen::Vector3d ego(m_xkk[0], m_xkk[1], m_xkk[2]);
	out.resize(idx.size());
	for (size_t i = 0; i < idx.size(); ++i)
	{
		const size_t s = idx[i];
		if (s < m_slots.size() && m_slots[s].kind == SlotKind::StaticLandmark)
		{
			const size_t k = slotStateIndex(s);
			const Eigen::Vector2d z =
				safeObserve(options.measurement_model, ego, Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]));
			out[i][0] = z[0];
			out[i][1] = z[1];
		}
		else
		{
			out[i][0] = 0;
			out[i][1] = 0;
		}
	}
}

void CDynamicKFSLAM2D::OnObservationJacobians(size_t s, KFMatrix_OxV& Hx, KFMatrix_OxF& Hy) const
{
	Hx.setZero();
	Hy.setZero();
	if (s >= m_slots.size() || m_slots[s].kind != SlotKind::StaticLandmark) return;
	const size_t k = slotStateIndex(s);
	models::Matrix23d J_z_x;
	Eigen::Matrix2d J_z_f;
	const Eigen::Vector3d ego(m_xkk[0], m_xkk[1], m_xkk[2]);
	models::observe(
		options.measurement_model, ego, Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]), &J_z_x, &J_z_f);
	if (options.first_estimate_jacobians) firstEstimateJacobians(m_slots[s].id, ego, J_z_x, J_z_f);
	Hx = J_z_x;
	Hy = J_z_f;
}

void CDynamicKFSLAM2D::OnSubstractObservationVectors(KFArray_OBS& A, const KFArray_OBS& B) const
{
	const Eigen::Vector2d d = models::innovation(
		options.measurement_model, Eigen::Vector2d(A[0], A[1]), Eigen::Vector2d(B[0], B[1]));
	A[0] = d[0];
	A[1] = d[1];
}

double CDynamicKFSLAM2D::gateThreshold() const
{
	// Chi-square quantile with 2 dof in closed form: F(x) = 1 - exp(-x/2).
	return options.innovation_gate > 0 ? -2.0 * std::log(1.0 - options.innovation_gate)
									   : std::numeric_limits<double>::infinity();
}

void CDynamicKFSLAM2D::OnGetObservationsAndDataAssociation(
	vector_KFArray_OBS& Z, std::vector<int>& da, const vector_KFArray_OBS& all_predictions,
	const KFMatrix& S, const std::vector<size_t>& lm_indices_in_S, const KFMatrix_OxO&)
{
	m_zToStatic.clear();
	Z.clear();
	da.clear();
	auto emit = [&](size_t i, int assoc) {
		KFArray_OBS z;
		z[0] = m_static[i].z[0];
		z[1] = m_static[i].z[1];
		Z.push_back(z);
		da.push_back(assoc);
		m_zToStatic.push_back(i);
	};
	if (options.sparse_static_update)
	{
		// Called between MRPT's prediction and update: update here and hand MRPT nothing; the
		// new landmarks are augmented from the updated state with the step's other new
		// entries, in one rewrite of the covariance (planFeatures, commit).
		sparseStaticUpdate();
		return;
	}
	recordPredictedEgo();  // MRPT's path: called after its prediction, before its update
	const double thr = gateThreshold();
	std::vector<int> sIdx;  // accepted rows of S
	std::vector<Eigen::Vector2d> nus;
	size_t numNew = 0;
	for (size_t i = 0; i < m_static.size(); ++i)
	{
		const auto it = m_staticSlot.find(m_static[i].id);
		if (it == m_staticSlot.end())
		{
			emit(i, -1);
			++numNew;
			continue;
		}
		const size_t q = size_t(
			std::find(lm_indices_in_S.begin(), lm_indices_in_S.end(), it->second) -
			lm_indices_in_S.begin());
		const Eigen::Vector2d nu = models::innovation(
			options.measurement_model, m_static[i].z,
			Eigen::Vector2d(all_predictions[it->second][0], all_predictions[it->second][1]));
		const Eigen::Matrix2d Sqq = S.asEigen().block<2, 2>(2 * q, 2 * q);
		if (nu.dot(Sqq.ldlt().solve(nu)) > thr)
		{
			++m_report.gated_out;
			continue;
		}
		emit(i, int(it->second));
		sIdx.insert(sIdx.end(), {int(2 * q), int(2 * q + 1)});
		nus.push_back(nu);
	}
	m_report.static_updates = nus.size();
	m_report.static_new = numNew;
	m_report.nis_static = 0;
	m_report.nis_static_dof = 2 * nus.size();
	if (!nus.empty())
	{
		Eigen::VectorXd nu(2 * nus.size());
		for (size_t j = 0; j < nus.size(); ++j) nu.segment<2>(2 * j) = nus[j];
		const Eigen::MatrixXd Ssub = S.asEigen()(sIdx, sIdx);
		m_report.nis_static = nu.dot(Ssub.ldlt().solve(nu));
	}
}

void CDynamicKFSLAM2D::sparseStaticUpdate()
{
	recordPredictedEgo();  // called right after MRPT's prediction
	const Eigen::Vector3d ego(m_xkk[0], m_xkk[1], m_xkk[2]);
	const double thr = gateThreshold();
	const auto P = m_pkk.asEigen();
	std::vector<int> idx{0, 1, 2};
	std::vector<models::Matrix23d> Jx;
	std::vector<Eigen::Matrix2d> Jf;
	std::vector<Eigen::Vector2d> nus;
	for (size_t i = 0; i < m_static.size(); ++i)
	{
		const auto it = m_staticSlot.find(m_static[i].id);
		if (it == m_staticSlot.end()) continue;
		const int si = int(slotStateIndex(it->second));
		models::Matrix23d J_z_x;
		Eigen::Matrix2d J_z_f;
		const Eigen::Vector2d zhat = models::observe(
			options.measurement_model, ego, Eigen::Vector2d(m_xkk[si], m_xkk[si + 1]), &J_z_x, &J_z_f);
		const Eigen::Vector2d nu = models::innovation(options.measurement_model, m_static[i].z, zhat);
		if (options.first_estimate_jacobians)
			firstEstimateJacobians(m_static[i].id, ego, J_z_x, J_z_f);  // nu stays at x_hat
		if (std::isfinite(thr))
		{
			const std::vector<int> loc{0, 1, 2, si, si + 1};
			Eigen::Matrix<double, 2, 5> Hi;
			Hi << J_z_x, J_z_f;
			const Eigen::Matrix2d Si = Hi * P(loc, loc) * Hi.transpose() + options.Sigma_v;
			if (nu.dot(Si.ldlt().solve(nu)) > thr)
			{
				++m_report.gated_out;
				continue;
			}
		}
		idx.insert(idx.end(), {si, si + 1});
		Jx.push_back(J_z_x);
		Jf.push_back(J_z_f);
		nus.push_back(nu);
	}
	const Eigen::Index k = Eigen::Index(nus.size());
	m_report.static_updates = size_t(k);
	m_report.nis_static = 0;
	m_report.nis_static_dof = size_t(2 * k);
	if (k == 0) return;
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * k, 3 + 2 * k);
	Eigen::VectorXd nu(2 * k);
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * k, 2 * k);
	for (Eigen::Index j = 0; j < k; ++j)
	{
		H.block<2, 3>(2 * j, 0) = Jx[j];
		H.block<2, 2>(2 * j, 3 + 2 * j) = Jf[j];
		nu.segment<2>(2 * j) = nus[j];
		R.block<2, 2>(2 * j, 2 * j) = options.Sigma_v;
	}
	auto x = m_xkk.asEigen();
	auto Pm = m_pkk.asEigen();
	m_report.nis_static = ekf::sparseUpdate(x, Pm, idx, H, nu, R);
	OnNormalizeStateVector();
}

// ------------------------------------------------------------------------------------------
// First-estimate Jacobians
// ------------------------------------------------------------------------------------------
void CDynamicKFSLAM2D::recordPredictedEgo()
{
	if (options.first_estimate_jacobians)
		m_predictedEgo = Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]);
}

void CDynamicKFSLAM2D::recordFirstEstimates()
{
	if (!options.first_estimate_jacobians) return;
	// A landmark's first estimate is its mean at the end of the step that initialized it (the
	// object steps and the smoothing may move it after its augmentation in that step). A
	// dropped landmark is forgotten: if seen again, it is a new state entry with a new one.
	std::set<int32_t> inState;
	for (size_t s = 0; s < m_slots.size(); ++s)
	{
		if (m_slots[s].kind != SlotKind::StaticLandmark) continue;
		inState.insert(m_slots[s].id);
		const size_t k = slotStateIndex(s);
		m_firstEstimate.emplace(m_slots[s].id, Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]));
	}
	for (auto it = m_firstEstimate.begin(); it != m_firstEstimate.end();)
		it = inState.count(it->first) ? std::next(it) : m_firstEstimate.erase(it);
}

void CDynamicKFSLAM2D::firstEstimateJacobians(
	int32_t id, const Eigen::Vector3d& ego, models::Matrix23d& J_z_x, Eigen::Matrix2d& J_z_f) const
{
	const auto it = m_firstEstimate.find(id);
	if (it == m_firstEstimate.end()) return;
	models::observe(options.measurement_model, ego, it->second, &J_z_x, &J_z_f);
}

std::optional<Eigen::Vector2d> CDynamicKFSLAM2D::firstEstimate(int32_t id) const
{
	const auto it = m_firstEstimate.find(id);
	if (it == m_firstEstimate.end()) return std::nullopt;
	return it->second;
}

std::optional<Eigen::Vector3d> CDynamicKFSLAM2D::lastPredictedEgo() const { return m_predictedEgo; }

void CDynamicKFSLAM2D::OnInverseObservationModel(
	const KFArray_OBS& in_z, KFArray_FEAT& yn, KFMatrix_FxV& dyn_dxv, KFMatrix_FxO& dyn_dhn) const
{
	models::Matrix23d J_f_x;
	Eigen::Matrix2d J_f_z;
	const Eigen::Vector2d f = models::inverseObserve(
		options.measurement_model, Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]),
		Eigen::Vector2d(in_z[0], in_z[1]), &J_f_x, &J_f_z);
	yn[0] = f[0];
	yn[1] = f[1];
	dyn_dxv = J_f_x;
	dyn_dhn = J_f_z;
}

void CDynamicKFSLAM2D::OnNewLandmarkAddedToMap(size_t in_obsIdx, size_t in_idxNewFeat)
{
	// New landmarks are added in observation order, i.e. in the order of the da == -1 entries.
	const size_t k = m_slots.size();
	if (in_idxNewFeat != k)
		throw std::logic_error("CDynamicKFSLAM2D: slot table out of step with MRPT's state");
	if (in_obsIdx >= m_zToStatic.size())
		throw std::logic_error("CDynamicKFSLAM2D: new landmark from an unknown observation");
	const int32_t id = m_static[m_zToStatic[in_obsIdx]].id;
	TSlot s;
	s.kind = SlotKind::StaticLandmark;
	s.id = id;
	s.step = m_step;
	m_slots.push_back(s);
	m_staticSlot[id] = k;
}

void CDynamicKFSLAM2D::OnNormalizeStateVector()
{
	m_xkk[2] = models::wrapToPi(m_xkk[2]);
	for (size_t s = 0; s < m_slots.size(); ++s)
		if (m_slots[s].kind == SlotKind::ObjectPoseB)
		{
			const size_t k = slotStateIndex(s);
			m_xkk[k] = models::wrapToPi(m_xkk[k]);
		}
}
}  // namespace dynslam
