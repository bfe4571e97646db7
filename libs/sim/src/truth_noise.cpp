/** @file truth_noise.cpp
 * The model-matched truth (truth_noise.h). */
#include "truth_noise.h"

#include <dynslam/core/models/se2.h>
#include <mrpt/random/RandomGenerators.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

namespace dynslam::sim::detail
{
Eigen::Vector3d trueStartPose(const TScenarioOptions& o)
{
	if (!o.start_from_prior) return Eigen::Vector3d::Zero();
	// A square root of the PSD prior (exact on a diagonal; Sigma_0 may be singular).
	const Eigen::Matrix3d& S = o.Sigma_0;
	Eigen::Matrix3d L;
	if (S == Eigen::Matrix3d(S.diagonal().asDiagonal()))
		L = S.diagonal().cwiseMax(0.0).cwiseSqrt().asDiagonal();
	else
	{
		const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(S);
		if (es.info() != Eigen::Success || es.eigenvalues().minCoeff() < -1e-12 * S.norm())
			throw std::invalid_argument("[Noise] sigma_0: not positive semi-definite");
		L = es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
	}
	mrpt::random::CRandomGenerator rng(uint32_t(o.noise_seed + 0x3C6EF372u));
	Eigen::Vector3d n;
	for (int i = 0; i < 3; ++i) n[i] = rng.drawGaussian1D_normalized();
	Eigen::Vector3d x0 = L * n;
	x0[2] = models::wrapToPi(x0[2]);
	return x0;
}

std::vector<std::vector<Eigen::Vector3d>> objectPoseOffsets(const TScenarioOptions& o,
                                                            size_t numObjects)
{
	const Eigen::Vector3d& q = o.object_accel_psd;
	if (q.isZero()) return {};
	const double dt = o.dt;
	// Cholesky factor of q [dt^3/3 dt^2/2; dt^2/2 dt] (models::cvProcessNoise), per unit q.
	const double l11 = std::sqrt(dt * dt * dt / 3), l21 = std::sqrt(3 * dt) / 2,
	             l22 = std::sqrt(dt) / 2;
	mrpt::random::CRandomGenerator rng(uint32_t(o.noise_seed + 0x78DDE6E6u));
	std::vector<std::vector<Eigen::Vector3d>> out(numObjects);
	for (auto& d : out)
	{
		d.assign(o.numSteps(), Eigen::Vector3d::Zero());
		Eigen::Vector3d rate = Eigen::Vector3d::Zero();
		for (size_t k = 1; k < d.size(); ++k)
			for (int i = 0; i < 3; ++i)
			{
				const double a = rng.drawGaussian1D_normalized();
				const double b = rng.drawGaussian1D_normalized();
				const double s = std::sqrt(q[i]);
				d[k][i] = d[k - 1][i] + dt * rate[i] + s * l11 * a;
				rate[i] += s * (l21 * a + l22 * b);
			}
	}
	return out;
}

Eigen::Matrix2Xd offsetFeatures(const Eigen::Matrix2Xd& F, const Eigen::Vector3d& d)
{
	const Eigen::Vector2d c = F.rowwise().mean();
	return (models::rot2(d[2]) * (F.colwise() - c)).colwise() + (c + d.head<2>());
}
}  // namespace dynslam::sim::detail
