#pragma once
/** @file align.h
 * SE(2) least-squares alignment of an estimated trajectory to the truth (Umeyama's closed form
 * in 2-D without scale; the TUM/evo "aligned ATE" convention). Pure Eigen; doc/metrics.md. */
#include <Eigen/Core>
#include <vector>

namespace dynslam::eval
{
/** Rigid 2-D transform q = (x, y, theta) with q(p) = R(theta) p + (x, y). */
struct TSE2Alignment
{
	Eigen::Vector3d q = Eigen::Vector3d::Zero();
	double rms = 0;  ///< sqrt(mean |truth_i - q(est_i)|^2) after the alignment
};

/** The q minimising sum |truth_i - (R est_i + t)|^2 (closed form: with centred points p_i, r_i
 * of est and truth, theta = atan2(sum p x r, sum p . r), t = mean(truth) - R mean(est)).
 * One point: translation only (theta = 0). Throws std::invalid_argument if the sizes differ or
 * there is no point. */
TSE2Alignment alignSE2(const std::vector<Eigen::Vector2d>& est,
                       const std::vector<Eigen::Vector2d>& truth);
}  // namespace dynslam::eval
