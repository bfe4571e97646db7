#pragma once
/** @file object_modes.h
 * The mode probabilities of multiple-model objects (object_model = mm, issue 28;
 * models/mode_mixture.h, doc/state-layout.md "Multiple-model objects"): per object, the
 * probabilities of the model's modes, updated each step by the object's readings (a GPB1-style
 * switch), their history for the outputs, and the moment-matched prediction they weight. One
 * module for both back-ends: the dynamic EKF (CDynamicKFSLAM2D_mm.cpp) and Alg. 1
 * (CAlg1Backend_objects.cpp) call predict() with their own likelihood of the readings. Pure
 * Eigen. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/estimator/object_motion_model.h>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace dynslam::estimator
{
/** Every mode's prediction of an object's motion state s = [pose; velocity]. */
struct TModePredictions
{
	std::vector<Eigen::VectorXd> s;  ///< s_j = f_j(s)
	std::vector<Eigen::MatrixXd> F;  ///< J_out_s of mode j
	std::vector<Eigen::MatrixXd> Q;  ///< process noise of mode j
};

/** The names of the model's modes (empty for a single model). */
std::vector<std::string> modeNames(const IObjectMotionModel& model);

/** One reading's sighting under a predicted object pose xi: its innovation (z (-) z_hat) and
 * the Jacobians of z_hat on the ego pose (2x3), on xi (2 x |xi|) and on the object's time-0
 * features (2 x 2n, all n of them). */
struct TReadingSighting
{
	Eigen::Vector2d nu;
	models::Matrix23d H_x;
	Eigen::MatrixXd H_xi, H_f0;
};
/** The sighting of reading r (0..m-1) of the object under the predicted pose xi. */
using TSightingFn = std::function<TReadingSighting(Eigen::Index r, const Eigen::VectorXd& xi)>;

/** log L_j of an object's m readings under each mode j's prediction (TLogLikelihoods for
 * CObjectModes::predict): the readings' innovations and Jacobians (sighting, at the pose part
 * pred.s[j].head(poseDim)) stacked into nu and H on the entries e = [ego (3); s (pred.s[j]'s
 * size, the velocity's columns 0); f_0 (the rest of P_e)], R = diag(Sigma_v, ..., Sigma_v),
 * then models::predictedReadingsLogLikelihood(P_e, 3, F_j, Q_j, H, nu, R). P_e: the prior
 * covariance of e. m = 0: empty (no readings). The stacking shared by the dynamic EKF
 * (CDynamicKFSLAM2D_mm.cpp) and Alg. 1 (CAlg1Backend_objects.cpp), which differ only in how
 * they sight a reading. Throws std::invalid_argument on sizes. */
Eigen::VectorXd readingsModeLogLikelihoods(const TModePredictions& pred, const Eigen::MatrixXd& P_e,
                                           Eigen::Index poseDim, Eigen::Index m,
                                           const Eigen::Matrix2d& Sigma_v,
                                           const TSightingFn& sighting);

class CObjectModes
{
public:
	/** log L_j of the object's readings of this step under each mode's prediction; an empty
	 * vector: no readings (the probabilities then follow the switching only). */
	using TLogLikelihoods = std::function<Eigen::VectorXd(const TModePredictions&)>;

	/** One object's step: its probabilities (the model's initial ones for a new object) updated
	 * by the switching and the readings (models::modePosterior), recorded at `step` (all steps,
	 * or the newest only with record = false), and the moment-matched prediction of s with
	 * prior covariance P_ss by the modes above models::kModePruneProbability. */
	models::TModeMixture predict(const IObjectMotionModel& model, int32_t obj, int step,
	                             const Eigen::VectorXd& s, const Eigen::MatrixXd& P_ss,
	                             const TLogLikelihoods& logLikelihoods, bool record);

	/** The current probabilities of every object predicted and not forgotten. */
	const std::map<int32_t, Eigen::VectorXd>& probabilities() const { return m_prob; }
	/** obj's probabilities recorded at `step`; nullptr if none. */
	const Eigen::VectorXd* at(int32_t obj, int step) const;
	/** Forgets the current probabilities of the objects not in `live` (their history stays). */
	void forget(const std::set<int32_t>& live);
	void clear();

private:
	std::map<int32_t, Eigen::VectorXd> m_prob;
	std::map<int32_t, std::vector<std::pair<int, Eigen::VectorXd>>> m_history;
};
}  // namespace dynslam::estimator
