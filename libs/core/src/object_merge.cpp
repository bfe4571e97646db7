#include <dynslam/core/models/object_merge.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>

#include <stdexcept>

namespace dynslam::models
{
Eigen::Matrix2Xd mergeObjectFeatures(const Eigen::VectorXd& xiL, const Eigen::Matrix2Xd& f0L,
                                     const Eigen::VectorXd& xiN, const Eigen::Matrix2Xd& fN,
                                     int foundersN, Eigen::MatrixXd* J_out_in)
{
	const Eigen::Index dL = xiL.size(), dN = xiN.size(), nL = f0L.cols(), m = fN.cols();
	if ((dL != 2 && dL != 3) || (dN != 0 && dN != 2 && dN != 3) || m < 1)
		throw std::invalid_argument("mergeObjectFeatures: poses of 2 or 3 entries (N: or 0)");
	if (dL == 3 && nL < 1)
		throw std::invalid_argument("mergeObjectFeatures: a 3-dof pose of L needs its founders");
	if (dN == 3 && (foundersN < 1 || foundersN > m))
		throw std::invalid_argument("mergeObjectFeatures: foundersN not in [1, m]");
	// w = g_N(xi_N, f^N): the features in the world frame now, and d vec(w) / d [xi_N; vec(fN)].
	Eigen::Matrix2Xd w = fN;
	Eigen::MatrixXd J_w_xiN = Eigen::MatrixXd::Zero(2 * m, dN);
	Eigen::MatrixXd J_w_fN = Eigen::MatrixXd::Identity(2 * m, 2 * m);
	if (dN == 2)
	{
		w.colwise() += xiN;
		for (Eigen::Index k = 0; k < m; ++k) J_w_xiN.block<2, 2>(2 * k, 0).setIdentity();
	}
	else if (dN == 3)
		w = objectPoseMap(Eigen::Vector3d(xiN), fN, &J_w_xiN, &J_w_fN, foundersN);
	// f' = g_L^-1(xi_L, w).
	const Eigen::Index cols = dL + 2 * nL + dN + 2 * m;
	Eigen::Matrix2Xd out(2, m);
	if (J_out_in) J_out_in->setZero(2 * m, cols);
	Eigen::Matrix2d Rt = Eigen::Matrix2d::Identity(), dRt = Eigen::Matrix2d::Zero();
	Eigen::Vector2d c0 = Eigen::Vector2d::Zero();
	if (dL == 3)
	{
		Rt = rot2(xiL[2]).transpose();
		dRt = rot2Derivative(xiL[2]).transpose();
		c0 = f0L.rowwise().mean();
	}
	for (Eigen::Index k = 0; k < m; ++k)
	{
		const Eigen::Vector2d r = w.col(k) - c0 - xiL.head<2>();
		out.col(k) = Rt * r + c0;
		if (!J_out_in) continue;
		Eigen::MatrixXd& J = *J_out_in;
		J.block<2, 2>(2 * k, 0) = -Rt;  // d f' / d (dx, dy)
		if (dL == 3)
		{
			J.block<2, 1>(2 * k, 2) = dRt * r;
			const Eigen::Matrix2d common = (Eigen::Matrix2d::Identity() - Rt) / double(nL);
			for (Eigen::Index j = 0; j < nL; ++j) J.block<2, 2>(2 * k, dL + 2 * j) = common;
		}
		// Through w: Rt d w_k / d [xi_N; fN].
		if (dN > 0) J.block(2 * k, dL + 2 * nL, 2, dN) = Rt * J_w_xiN.middleRows(2 * k, 2);
		J.block(2 * k, dL + 2 * nL + dN, 2, 2 * m) = Rt * J_w_fN.middleRows(2 * k, 2);
	}
	return out;
}
}  // namespace dynslam::models
