/** CDynamicKFSLAM2D: MRPT's Kalman-filter hooks, used by MRPT's update engine
 * (static_update = mrpt): runOneKalmanIteration with the prediction skipped (the prediction is
 * Alg. 7 by ekf::propagate, for every engine) and only the tracked static landmarks handed to
 * MRPT (new ones are augmented by the filter, CDynamicKFSLAM2D_objects.cpp). */
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/ekf/CMrptUpdateEngine.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <stdexcept>

namespace dynslam
{
estimator::TUpdateResult CMrptUpdateEngine::update(
    Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
    const std::vector<estimator::TStaticObservation>& obs, const estimator::TUpdateContext& ctx)
{
	if (x.data() != &m_kf.m_xkk[0] || P.data() != m_kf.m_cov.view().data())
		throw std::invalid_argument("CMrptUpdateEngine: works on its filter's own storage only");
	return m_kf.runMrptUpdate(obs, ctx);
}

estimator::TUpdateResult CDynamicKFSLAM2D::runMrptUpdate(
    const std::vector<estimator::TStaticObservation>& obs, const estimator::TUpdateContext& ctx)
{
	m_mrptObs = obs;
	m_mrptCtx = ctx;
	m_mrptResult = estimator::TUpdateResult();
	syncPkk();  // MRPT's update works on m_pkk
	runOneKalmanIteration();
	setCov(m_pkk.asEigen());
	m_pkkStale = false;
	m_mrptObs.clear();
	return m_mrptResult;
}

void CDynamicKFSLAM2D::OnGetAction(KFArray_ACT& u) const
{
	for (int i = 0; i < 3; ++i) u[i] = m_in.u[i];
}

void CDynamicKFSLAM2D::OnTransitionModel(const KFArray_ACT&, KFArray_VEH&,
                                         bool& out_skipPrediction) const
{
	// The prediction (Alg. 7) is ekf::propagate, done before the update for every engine.
	out_skipPrediction = true;
}

void CDynamicKFSLAM2D::OnTransitionJacobian(KFMatrix_VxV& F) const
{
	Eigen::Matrix3d J_out_x;
	models::composePose(Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]), m_in.u, &J_out_x);
	F = J_out_x;
}

void CDynamicKFSLAM2D::OnTransitionNoise(KFMatrix_VxV& Q) const
{
	// Noise on the robot-frame increment, mapped by J_out_u = blkdiag(R(theta), 1): this is
	// CPosePDFGaussian::rotateCov(theta), as in CRangeBearingKFSLAM2D.
	Eigen::Matrix3d J_out_u;
	models::composePose(Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]), Eigen::Vector3d::Zero(),
	                    nullptr, &J_out_u);
	const Eigen::Matrix3d& S = options.motion_noise_from_action ? m_in.U : options.Sigma_w;
	Q = J_out_u * S * J_out_u.transpose();
}

void CDynamicKFSLAM2D::OnGetObservationNoise(KFMatrix_OxO& R) const { R = m_mrptCtx.R; }

void CDynamicKFSLAM2D::OnPreComputingPredictions(const vector_KFArray_OBS&,
                                                 std::vector<size_t>& out_idx) const
{
	// IDs are known: predict exactly the tracked static landmarks read in this step.
	out_idx.clear();
	for (const auto& o : m_mrptObs) out_idx.push_back(m_layout.slotOf(m_staticBlock.at(o.id)));
}

namespace
{
/** h() from the sensor's world pose xs = x (+) s that never throws (MRPT may predict slots
 * that are not read). */
Eigen::Vector2d safeObserve(models::MeasurementModel model, const Eigen::Vector3d& xs,
                            const Eigen::Vector2d& f)
{
	if (model == models::MeasurementModel::RangeBearing && (f - xs.head<2>()).squaredNorm() == 0)
		return Eigen::Vector2d::Zero();
	return models::observe(model, xs, f);
}
}  // namespace

void CDynamicKFSLAM2D::OnObservationModel(const std::vector<size_t>& idx,
                                          vector_KFArray_OBS& out) const
{
	const Eigen::Vector3d xs = models::sensorPoseInWorld(
	    Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]), m_mrptCtx.sensor_pose);
	out.resize(idx.size());
	for (size_t i = 0; i < idx.size(); ++i)
	{
		const size_t s = idx[i];
		out[i][0] = out[i][1] = 0;
		if (s >= m_slots.size() || m_slots[s].kind != SlotKind::StaticLandmark) continue;
		const int k = m_layout.first(m_layout.blockAtSlot(s));
		const Eigen::Vector2d z =
		    safeObserve(m_mrptCtx.model, xs, Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]));
		out[i][0] = z[0];
		out[i][1] = z[1];
	}
}

void CDynamicKFSLAM2D::OnObservationJacobians(size_t s, KFMatrix_OxV& Hx, KFMatrix_OxF& Hy) const
{
	Hx.setZero();
	Hy.setZero();
	if (s >= m_slots.size() || m_slots[s].kind != SlotKind::StaticLandmark) return;
	const int k = m_layout.first(m_layout.blockAtSlot(s));
	models::Matrix23d J_z_x;
	Eigen::Matrix2d J_z_f;
	const Eigen::Vector3d ego(m_xkk[0], m_xkk[1], m_xkk[2]);
	models::observeFromSensor(m_mrptCtx.model, ego, m_mrptCtx.sensor_pose,
	                          Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]), &J_z_x, &J_z_f);
	if (m_mrptCtx.jacobians) m_mrptCtx.jacobians(m_slots[s].id, ego, J_z_x, J_z_f);
	Hx = J_z_x;
	Hy = J_z_f;
}

void CDynamicKFSLAM2D::OnSubstractObservationVectors(KFArray_OBS& A, const KFArray_OBS& B) const
{
	const Eigen::Vector2d d = models::innovation(m_mrptCtx.model, Eigen::Vector2d(A[0], A[1]),
	                                             Eigen::Vector2d(B[0], B[1]));
	A[0] = d[0];
	A[1] = d[1];
}

void CDynamicKFSLAM2D::OnGetObservationsAndDataAssociation(
    vector_KFArray_OBS& Z, std::vector<int>& da, const vector_KFArray_OBS& all_predictions,
    const KFMatrix& S, const std::vector<size_t>& lm_indices_in_S, const KFMatrix_OxO&)
{
	Z.clear();
	da.clear();
	std::vector<int> sIdx;  // accepted rows of S
	std::vector<Eigen::Vector2d> nus;
	for (const auto& o : m_mrptObs)
	{
		const size_t slot = m_layout.slotOf(m_staticBlock.at(o.id));
		const size_t q = size_t(std::find(lm_indices_in_S.begin(), lm_indices_in_S.end(), slot) -
		                        lm_indices_in_S.begin());
		const Eigen::Vector2d nu =
		    models::innovation(m_mrptCtx.model, o.z,
		                       Eigen::Vector2d(all_predictions[slot][0], all_predictions[slot][1]));
		const Eigen::Matrix2d Sqq = S.asEigen().block<2, 2>(2 * q, 2 * q);
		if (nu.dot(Sqq.ldlt().solve(nu)) > m_mrptCtx.gate_threshold)
		{
			++m_mrptResult.gated_out;
			continue;
		}
		KFArray_OBS z;
		z[0] = o.z[0];
		z[1] = o.z[1];
		Z.push_back(z);
		da.push_back(int(slot));
		sIdx.insert(sIdx.end(), {int(2 * q), int(2 * q + 1)});
		nus.push_back(nu);
	}
	m_mrptResult.updates = nus.size();
	m_mrptResult.nis_dof = 2 * nus.size();
	if (nus.empty()) return;
	Eigen::VectorXd nu(2 * nus.size());
	for (size_t j = 0; j < nus.size(); ++j) nu.segment<2>(2 * j) = nus[j];
	const Eigen::MatrixXd Ssub = S.asEigen()(sIdx, sIdx);
	m_mrptResult.nis = nu.dot(Ssub.ldlt().solve(nu));
}

void CDynamicKFSLAM2D::OnInverseObservationModel(const KFArray_OBS& in_z, KFArray_FEAT& yn,
                                                 KFMatrix_FxV& dyn_dxv, KFMatrix_FxO& dyn_dhn) const
{
	models::Matrix23d J_f_x;
	Eigen::Matrix2d J_f_z;
	const Eigen::Vector2d f = models::inverseObserveFromSensor(
	    options.measurement_model, Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]), m_in.sensor_pose,
	    Eigen::Vector2d(in_z[0], in_z[1]), &J_f_x, &J_f_z);
	yn[0] = f[0];
	yn[1] = f[1];
	dyn_dxv = J_f_x;
	dyn_dhn = J_f_z;
}

void CDynamicKFSLAM2D::OnNewLandmarkAddedToMap(size_t, size_t)
{
	// MRPT is never handed a new landmark (da == -1): the filter augments them itself.
	throw std::logic_error(
	    "CDynamicKFSLAM2D: MRPT added a landmark; the slot table has one writer");
}

void CDynamicKFSLAM2D::OnNormalizeStateVector()
{
	m_xkk[2] = models::wrapToPi(m_xkk[2]);
	for (size_t b = 0; b < m_layout.size(); ++b)
		if (m_layout[b].kind == estimator::BlockKind::ObjectPose && m_layout[b].dim == 3)
		{
			const int k = m_layout.first(b) + 2;
			m_xkk[k] = models::wrapToPi(m_xkk[k]);
		}
}
}  // namespace dynslam
