#pragma once
/** @file mrpt_kalman_adapter.h
 * (Internal to dynslam::ekf.) The bodies of CDynamicKFSLAM2D's CKalmanFilterCapable hooks (the
 * OnX overrides stay members of the facade, as MRPT's virtual functions, and delegate here) and
 * MRPT's update engine (static_update = mrpt, CMrptUpdateEngine): runOneKalmanIteration with the
 * prediction skipped (the prediction is Alg. 7 by ekf::propagate, for every engine) and only the
 * tracked static landmarks handed to MRPT (new ones are augmented by the filter). The adapter
 * owns what one such update needs between MRPT's calls of the hooks: the readings handed to
 * MRPT, the update context and the result. OnNormalizeStateVector (normalize) serves every
 * engine: it wraps the ego's and the 3-dof object poses' headings. */
#include <vector>

#include "modules/filter_module.h"

namespace dynslam::ekf
{
class CMrptKalmanAdapter
{
public:
	using KF = CDynamicKFSLAM2D;
	/** The filter whose hooks it serves (it outlives the adapter). */
	explicit CMrptKalmanAdapter(CDynamicKFSLAM2D& f) : m_f(f) {}
	/** MRPT's update (CMrptUpdateEngine::update): x and P must be the filter's own storage. */
	estimator::TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                                const std::vector<estimator::TStaticObservation>& obs,
	                                const estimator::TUpdateContext& ctx);

	// the hooks' bodies (CDynamicKFSLAM2D's OnX of the same meaning)
	void transitionJacobian(KF::KFMatrix_VxV& F) const;
	void transitionNoise(KF::KFMatrix_VxV& Q) const;
	void observationNoise(KF::KFMatrix_OxO& R) const { R = m_ctx.R; }
	void preComputingPredictions(std::vector<size_t>& out_idx) const;
	void observationModel(const std::vector<size_t>& idx, KF::vector_KFArray_OBS& out) const;
	void observationJacobians(size_t s, KF::KFMatrix_OxV& Hx, KF::KFMatrix_OxF& Hy) const;
	void subtractObservations(KF::KFArray_OBS& A, const KF::KFArray_OBS& B) const;
	void observationsAndDataAssociation(KF::vector_KFArray_OBS& Z, std::vector<int>& da,
	                                    const KF::vector_KFArray_OBS& all_predictions,
	                                    const KF::KFMatrix& S,
	                                    const std::vector<size_t>& lm_indices_in_S);
	void inverseObservationModel(const KF::KFArray_OBS& in_z, KF::KFArray_FEAT& yn,
	                             KF::KFMatrix_FxV& dyn_dxv, KF::KFMatrix_FxO& dyn_dhn) const;
	void normalize();

private:
	TFilterView view() const { return {m_f}; }
	CDynamicKFSLAM2D& m_f;
	std::vector<estimator::TStaticObservation> m_obs;  ///< the readings handed to MRPT
	estimator::TUpdateContext m_ctx;
	estimator::TUpdateResult m_result;
};
}  // namespace dynslam::ekf
