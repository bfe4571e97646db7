/** CDynamicKFSLAM2D: MRPT's Kalman-filter hooks (CKalmanFilterCapable's virtual functions),
 * used by MRPT's update engine (static_update = mrpt). Their bodies, and what one MRPT update
 * needs between MRPT's calls of them: ekf::CMrptKalmanAdapter (src/mrpt_kalman_adapter.h). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <stdexcept>

#include "mrpt_kalman_adapter.h"

namespace dynslam
{
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
	m_mrpt->transitionJacobian(F);
}

void CDynamicKFSLAM2D::OnTransitionNoise(KFMatrix_VxV& Q) const { m_mrpt->transitionNoise(Q); }

void CDynamicKFSLAM2D::OnGetObservationNoise(KFMatrix_OxO& R) const { m_mrpt->observationNoise(R); }

void CDynamicKFSLAM2D::OnPreComputingPredictions(const vector_KFArray_OBS&,
                                                 std::vector<size_t>& out_idx) const
{
	m_mrpt->preComputingPredictions(out_idx);
}

void CDynamicKFSLAM2D::OnObservationModel(const std::vector<size_t>& idx,
                                          vector_KFArray_OBS& out) const
{
	m_mrpt->observationModel(idx, out);
}

void CDynamicKFSLAM2D::OnObservationJacobians(size_t s, KFMatrix_OxV& Hx, KFMatrix_OxF& Hy) const
{
	m_mrpt->observationJacobians(s, Hx, Hy);
}

void CDynamicKFSLAM2D::OnSubstractObservationVectors(KFArray_OBS& A, const KFArray_OBS& B) const
{
	m_mrpt->subtractObservations(A, B);
}

void CDynamicKFSLAM2D::OnGetObservationsAndDataAssociation(
    vector_KFArray_OBS& Z, std::vector<int>& da, const vector_KFArray_OBS& all_predictions,
    const KFMatrix& S, const std::vector<size_t>& lm_indices_in_S, const KFMatrix_OxO&)
{
	m_mrpt->observationsAndDataAssociation(Z, da, all_predictions, S, lm_indices_in_S);
}

void CDynamicKFSLAM2D::OnInverseObservationModel(const KFArray_OBS& in_z, KFArray_FEAT& yn,
                                                 KFMatrix_FxV& dyn_dxv, KFMatrix_FxO& dyn_dhn) const
{
	m_mrpt->inverseObservationModel(in_z, yn, dyn_dxv, dyn_dhn);
}

void CDynamicKFSLAM2D::OnNewLandmarkAddedToMap(size_t, size_t)
{
	// MRPT is never handed a new landmark (da == -1): the filter augments them itself.
	throw std::logic_error(
	    "CDynamicKFSLAM2D: MRPT added a landmark; the slot table has one writer");
}

void CDynamicKFSLAM2D::OnNormalizeStateVector() { m_mrpt->normalize(); }
}  // namespace dynslam
