#pragma once
/** @file mode_mixture.h
 * Multiple-model prediction of one object inside the joint EKF (issue 28, object_model = mm;
 * doc/state-layout.md "Multiple-model objects"). An object's motion state s = [xi; v] is
 * predicted under M modes, s_j = f_j(s) with Jacobian F_j and process noise Q_j. With mode
 * weights w_j (sum 1) the joint prediction is the moment-matched mixture of the M joint
 * Gaussian predictions: with s_bar = sum_j w_j s_j, d_j = s_j - s_bar,
 *
 *   P'_ss = sum_j w_j (F_j P_ss F_j^T + Q_j + d_j d_j^T),   P'_sr = (sum_j w_j F_j) P_sr,
 *
 * r every other state entry (unchanged). This is one linear prediction with F_bar = sum w_j F_j
 * and the effective process noise
 *
 *   Q_eff = P'_ss - F_bar P_ss F_bar^T = sum_j w_j ((F_j - F_bar) P_ss (F_j - F_bar)^T + Q_j
 *           + d_j d_j^T)  (positive semidefinite),
 *
 * so ekf::predictSubset(x, P, idx, s_bar, F_bar, Q_eff) applies it in O(n |s|^2).
 *
 * Mode probabilities (a GPB1-style switch driven by this step's readings, Blom and Bar-Shalom
 * 1988): prior mu^- = Pi^T mu (Pi[i][j] = P(mode j at k | mode i at k-1)), posterior
 * mu_j proportional to mu^-_j L_j with L_j the likelihood of the object's readings under mode
 * j's prediction; no readings: mu = mu^-. The EKF then predicts with w = mu and updates once
 * with the readings (the approximation: one update of the merged prior instead of M updates
 * merged afterwards; equal when one mode has all the weight). Pure math; no MRPT. */
#include <Eigen/Core>
#include <vector>

namespace dynslam::models
{
/** The moment-matched prediction of a mixture of modes (see the file comment). */
struct TModeMixture
{
	Eigen::VectorXd s;      ///< s_bar
	Eigen::MatrixXd F;      ///< F_bar
	Eigen::MatrixXd Q_eff;  ///< Q_eff (symmetric PSD)
};

/** s_j, F_j, Q_j: one per mode (equal sizes); w: weights >= 0 summing to 1 (within 1e-9);
 * P_ss: the prior covariance of s. angleIdx: an entry of s that is an angle (its d_j wrapped
 * to (-pi, pi] around s_bar; -1: none). Throws std::invalid_argument on sizes or weights. */
TModeMixture mixModes(const std::vector<Eigen::VectorXd>& s_j,
                      const std::vector<Eigen::MatrixXd>& F_j,
                      const std::vector<Eigen::MatrixXd>& Q_j, const Eigen::VectorXd& w,
                      const Eigen::MatrixXd& P_ss, int angleIdx = -1);

/** Markov switching matrix with stay probability 1 - p_switch and p_switch spread evenly over
 * the other M - 1 modes (M >= 2, p_switch in [0, 1)). Rows sum to 1. */
Eigen::MatrixXd uniformSwitching(int M, double p_switch);

/** Mode posterior mu_j proportional to (Pi^T mu)_j exp(logL_j) (log-sum-exp; logL empty: the
 * prior Pi^T mu). A posterior with no mass (every logL_j = -inf) keeps the prior. Throws
 * std::invalid_argument on sizes. */
Eigen::VectorXd modePosterior(const Eigen::VectorXd& mu, const Eigen::MatrixXd& Pi,
                              const Eigen::VectorXd& logL);

/** Modes below this probability are left out of the prediction (their probabilities are still
 * tracked): a mode the readings rule out would otherwise add its process noise and its spread
 * at its tiny weight every step (the manoeuvre mode's Q is 10^7 times cv's on the tunnel). */
constexpr double kModePruneProbability = 1e-3;

/** The mixing weights of mode probabilities mu: entries below kModePruneProbability set to 0,
 * the rest renormalised (mu unchanged if every entry is below it). */
Eigen::VectorXd prunedWeights(const Eigen::VectorXd& mu);

/** Gaussian log-likelihood of innovation nu with covariance S, without the constant
 * -dim/2 log(2 pi) (equal for every mode): -0.5 (nu^T S^-1 nu + log det S). S must be
 * positive definite (else std::runtime_error). */
double gaussianLogLikelihood(const Eigen::VectorXd& nu, const Eigen::MatrixXd& S);

/** The log-likelihood (gaussianLogLikelihood) of readings under one mode's joint prediction.
 * P_e: the prior covariance of the entries e the readings depend on, with the object's motion
 * state s at rows [sOffset, sOffset + F.rows()); the mode predicts s' = f(s) with Jacobian F and
 * noise Q, so P'_e = T P_e T^T + Q on s' (T: the identity with F on s). nu: the stacked
 * innovations of the readings under the mode's predicted mean, H their Jacobian on the
 * predicted e, R their noise: log N(nu; 0, H P'_e H^T + R). Used by the dynamic EKF and by
 * Alg. 1 (object_model = mm). Throws std::invalid_argument on sizes. */
double predictedReadingsLogLikelihood(const Eigen::MatrixXd& P_e, Eigen::Index sOffset,
                                      const Eigen::MatrixXd& F, const Eigen::MatrixXd& Q,
                                      const Eigen::MatrixXd& H, const Eigen::VectorXd& nu,
                                      const Eigen::MatrixXd& R);
}  // namespace dynslam::models
