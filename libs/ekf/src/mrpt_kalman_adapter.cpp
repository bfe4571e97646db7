/** MRPT's Kalman-filter hooks of CDynamicKFSLAM2D and MRPT's update engine
 * (mrpt_kalman_adapter.h). */
#include "mrpt_kalman_adapter.h"

#include <dynslam/core/models/se2.h>
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
	return m_kf.m_mrpt->update(x, P, obs, ctx);
}

namespace ekf
{
estimator::TUpdateResult CMrptKalmanAdapter::update(
    Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
    const std::vector<estimator::TStaticObservation>& obs, const estimator::TUpdateContext& ctx)
{
	TFilterAccess a{m_f};
	if (x.data() != a.mean().data() || P.data() != a.covBuffer().view().data())
		throw std::invalid_argument("CMrptUpdateEngine: works on its filter's own storage only");
	m_obs = obs;
	m_ctx = ctx;
	m_result = estimator::TUpdateResult();
	a.runMrptIteration();  // MRPT's update works on its copy m_pkk, written back
	m_obs.clear();
	return m_result;
}

void CMrptKalmanAdapter::transitionJacobian(KF::KFMatrix_VxV& F) const
{
	Eigen::Matrix3d J_out_x;
	models::composePose(view().ego(), view().input().u, &J_out_x);
	F = J_out_x;
}

void CMrptKalmanAdapter::transitionNoise(KF::KFMatrix_VxV& Q) const
{
	// Noise on the robot-frame increment, mapped by J_out_u = blkdiag(R(theta), 1): this is
	// CPosePDFGaussian::rotateCov(theta), as in CRangeBearingKFSLAM2D.
	const TFilterView v = view();
	Eigen::Matrix3d J_out_u;
	models::composePose(v.ego(), Eigen::Vector3d::Zero(), nullptr, &J_out_u);
	const Eigen::Matrix3d& S =
	    v.options().motion_noise_from_action ? v.input().U : v.options().Sigma_w;
	Q = J_out_u * S * J_out_u.transpose();
}

void CMrptKalmanAdapter::preComputingPredictions(std::vector<size_t>& out_idx) const
{
	// IDs are known: predict exactly the tracked static landmarks read in this step.
	const TFilterView v = view();
	out_idx.clear();
	for (const auto& o : m_obs) out_idx.push_back(v.layout().slotOf(v.staticBlocks().at(o.id)));
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

void CMrptKalmanAdapter::observationModel(const std::vector<size_t>& idx,
                                          KF::vector_KFArray_OBS& out) const
{
	const TFilterView v = view();
	const auto x = v.mean();
	const std::vector<TSlot>& slots = v.slots();
	const Eigen::Vector3d xs = models::sensorPoseInWorld(v.ego(), m_ctx.sensor_pose);
	out.resize(idx.size());
	for (size_t i = 0; i < idx.size(); ++i)
	{
		const size_t s = idx[i];
		out[i][0] = out[i][1] = 0;
		if (s >= slots.size() || slots[s].kind != SlotKind::StaticLandmark) continue;
		const int k = v.layout().first(v.layout().blockAtSlot(s));
		const Eigen::Vector2d z = safeObserve(m_ctx.model, xs, Eigen::Vector2d(x[k], x[k + 1]));
		out[i][0] = z[0];
		out[i][1] = z[1];
	}
}

void CMrptKalmanAdapter::observationJacobians(size_t s, KF::KFMatrix_OxV& Hx,
                                              KF::KFMatrix_OxF& Hy) const
{
	const TFilterView v = view();
	const std::vector<TSlot>& slots = v.slots();
	Hx.setZero();
	Hy.setZero();
	if (s >= slots.size() || slots[s].kind != SlotKind::StaticLandmark) return;
	const int k = v.layout().first(v.layout().blockAtSlot(s));
	models::Matrix23d J_z_x;
	Eigen::Matrix2d J_z_f;
	const Eigen::Vector3d ego = v.ego();
	const auto x = v.mean();
	models::observeFromSensor(m_ctx.model, ego, m_ctx.sensor_pose, Eigen::Vector2d(x[k], x[k + 1]),
	                          &J_z_x, &J_z_f);
	if (m_ctx.jacobians) m_ctx.jacobians(slots[s].id, ego, J_z_x, J_z_f);
	Hx = J_z_x;
	Hy = J_z_f;
}

void CMrptKalmanAdapter::subtractObservations(KF::KFArray_OBS& A, const KF::KFArray_OBS& B) const
{
	const Eigen::Vector2d d =
	    models::innovation(m_ctx.model, Eigen::Vector2d(A[0], A[1]), Eigen::Vector2d(B[0], B[1]));
	A[0] = d[0];
	A[1] = d[1];
}

void CMrptKalmanAdapter::observationsAndDataAssociation(
    KF::vector_KFArray_OBS& Z, std::vector<int>& da, const KF::vector_KFArray_OBS& all_predictions,
    const KF::KFMatrix& S, const std::vector<size_t>& lm_indices_in_S)
{
	const TFilterView v = view();
	Z.clear();
	da.clear();
	std::vector<int> sIdx;  // accepted rows of S
	std::vector<Eigen::Vector2d> nus;
	for (const auto& o : m_obs)
	{
		const size_t slot = v.layout().slotOf(v.staticBlocks().at(o.id));
		const size_t q = size_t(std::find(lm_indices_in_S.begin(), lm_indices_in_S.end(), slot) -
		                        lm_indices_in_S.begin());
		const Eigen::Vector2d nu = models::innovation(
		    m_ctx.model, o.z, Eigen::Vector2d(all_predictions[slot][0], all_predictions[slot][1]));
		const Eigen::Matrix2d Sqq = S.asEigen().block<2, 2>(2 * q, 2 * q);
		if (nu.dot(Sqq.ldlt().solve(nu)) > m_ctx.gate_threshold)
		{
			++m_result.gated_out;
			continue;
		}
		KF::KFArray_OBS z;
		z[0] = o.z[0];
		z[1] = o.z[1];
		Z.push_back(z);
		da.push_back(int(slot));
		sIdx.insert(sIdx.end(), {int(2 * q), int(2 * q + 1)});
		nus.push_back(nu);
	}
	m_result.updates = nus.size();
	m_result.nis_dof = 2 * nus.size();
	if (nus.empty()) return;
	Eigen::VectorXd nu(2 * nus.size());
	for (size_t j = 0; j < nus.size(); ++j) nu.segment<2>(2 * j) = nus[j];
	const Eigen::MatrixXd Ssub = S.asEigen()(sIdx, sIdx);
	m_result.nis = nu.dot(Ssub.ldlt().solve(nu));
}

void CMrptKalmanAdapter::inverseObservationModel(const KF::KFArray_OBS& in_z, KF::KFArray_FEAT& yn,
                                                 KF::KFMatrix_FxV& dyn_dxv,
                                                 KF::KFMatrix_FxO& dyn_dhn) const
{
	const TFilterView v = view();
	models::Matrix23d J_f_x;
	Eigen::Matrix2d J_f_z;
	const Eigen::Vector2d f = models::inverseObserveFromSensor(
	    v.options().measurement_model, v.ego(), v.input().sensor_pose,
	    Eigen::Vector2d(in_z[0], in_z[1]), &J_f_x, &J_f_z);
	yn[0] = f[0];
	yn[1] = f[1];
	dyn_dxv = J_f_x;
	dyn_dhn = J_f_z;
}

void CMrptKalmanAdapter::normalize()
{
	TFilterAccess a{m_f};
	auto x = a.mean();
	const estimator::CPaddedLayout& L = a.layout();
	x[2] = models::wrapToPi(x[2]);
	for (size_t b = 0; b < L.size(); ++b)
		if (L[b].kind == estimator::BlockKind::ObjectPose && L[b].dim == 3)
		{
			const int k = L.first(b) + 2;
			x[k] = models::wrapToPi(x[k]);
		}
}
}  // namespace ekf
}  // namespace dynslam
