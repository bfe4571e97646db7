#pragma once
/** @file markov_motion.h
 * Markov-switching object motion (issue 28 item 4; `[ObjectMotion] model = markov`,
 * doc/simulator.md "Markov-switching object motion"): the model-matched truth of the
 * multiple-model filter estimator::CMultipleModel. Its modes, in its order, with the same
 * models of models/object_motion.h:
 *   0 stationary: xi' = xi, v' = 0, noise Q(accel_psd);
 *   1 cv:         models::cvPredict,   Q(accel_psd);
 *   2 turn:       models::ctrvPredict, Q(accel_psd);
 *   3 manoeuvre:  models::cvPredict,   Q(manoeuvre_psd);
 * Q(q) = models::cvProcessNoise(q, dt) on s = [xi; v]. Per step: the mode switches first
 * (stay with 1 - switch_prob, else one of the other three with equal probability:
 * models::uniformSwitching), then s' = f_mode(s) + w, w ~ N(0, Q_mode). */
#include <dynslam/sim/TScenarioOptions.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace dynslam::sim
{
constexpr int kMarkovModeCount = 4;

/** "stationary", "cv", "turn", "manoeuvre" (std::out_of_range otherwise). */
std::string markovModeName(int mode);

/** The noise-free step of `mode` for s = [xi; v] (4 or 6 entries) over dt. */
Eigen::VectorXd markovModeStep(int mode, const Eigen::VectorXd& s, double dt);

/** The process noise of `mode` for d = 2 or 3 axes (2d x 2d). */
Eigen::MatrixXd markovModeNoise(int mode, const TObjectMotionOptions& m, int d, double dt);

/** One object's Markov-switching motion: mode[k] and state[k] = [xi_k; v_k], k = 0..steps. */
struct TMarkovTrack
{
	std::vector<int> mode;
	std::vector<Eigen::VectorXd> state;
};

/** The tracks of objects starting at s0[i] = [0; v0] (4 or 6 entries; 4: a translation-only
 * object) in o.object_motion.initial_mode, over o.numSteps() steps of o.dt. One private
 * MT19937 seeded with (noise_seed + 0xB5297A4D) mod 2^32; objects in index order, per step two
 * uniforms (switch?, to which mode; both always drawn) and two standard normals per axis.
 * Throws std::invalid_argument if o.object_motion.markov is false or a state has a wrong size. */
std::vector<TMarkovTrack> markovObjectTracks(const TScenarioOptions& o,
                                             const std::vector<Eigen::VectorXd>& s0);
}  // namespace dynslam::sim
