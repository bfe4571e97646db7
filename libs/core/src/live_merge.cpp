#include <dynslam/core/models/live_merge.h>

#include <stdexcept>

namespace dynslam::models
{
Eigen::VectorXd rigidVelocityResidual(const Eigen::Vector3d& xiA, const Eigen::Matrix2Xd& f0A,
                                      const Eigen::Vector3d& vA, const Eigen::VectorXd& xiB,
                                      const Eigen::Matrix2Xd& f0B, const Eigen::VectorXd& vB,
                                      Eigen::MatrixXd* J_out_in)
{
	const Eigen::Index nA = f0A.cols(), nB = f0B.cols(), dB = xiB.size();
	if (nA < 1 || nB < 1 || (dB != 2 && dB != 3) || vB.size() != dB || (dB == 2 && nB != 1))
		throw std::invalid_argument("rigidVelocityResidual: wrong sizes");
	const Eigen::Vector2d pA = f0A.rowwise().mean() + xiA.head<2>();
	const Eigen::Vector2d pB = f0B.rowwise().mean() + xiB.head<2>();
	const Eigen::Vector2d d = pB - pA;
	const Eigen::Vector2d perp(-d.y(), d.x());
	Eigen::VectorXd r(dB);
	r.head<2>() = vB.head<2>() - vA.head<2>() - vA[2] * perp;
	if (dB == 3) r[2] = vB[2] - vA[2];
	if (!J_out_in) return r;
	// Column offsets of the input blocks.
	const Eigen::Index cxiA = 0, cfA = 3, cvA = 3 + 2 * nA, cxiB = cvA + 3, cfB = cxiB + dB,
	                   cvB = cfB + 2 * nB;
	Eigen::MatrixXd& J = *J_out_in;
	J.setZero(dB, cvB + dB);
	Eigen::Matrix2d K;  // d (omega_A perp(d)) / d d = omega_A [0 -1; 1 0]
	K << 0, -vA[2], vA[2], 0;
	J.block<2, 2>(0, cxiA) = K;  // d r / d p_A = +K, d p_A / d (dx, dy) = I
	for (Eigen::Index j = 0; j < nA; ++j) J.block<2, 2>(0, cfA + 2 * j) = K / double(nA);
	J.block<2, 2>(0, cvA) = -Eigen::Matrix2d::Identity();
	J.block<2, 1>(0, cvA + 2) = -perp;
	J.block<2, 2>(0, cxiB) = -K;
	for (Eigen::Index j = 0; j < nB; ++j) J.block<2, 2>(0, cfB + 2 * j) = -K / double(nB);
	J.block<2, 2>(0, cvB) = Eigen::Matrix2d::Identity();
	if (dB == 3)
	{
		J(2, cvA + 2) = -1;
		J(2, cvB + 2) = 1;
	}
	return r;
}
}  // namespace dynslam::models
