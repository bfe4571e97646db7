#include <dynslam/estimator/update_engine.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

namespace dynslam::estimator
{
double gateThreshold2Dof(double p)
{
	return p > 0 ? -2.0 * std::log(1.0 - p) : std::numeric_limits<double>::infinity();
}

TUpdateResult CSparseUpdateEngine::update(Eigen::Ref<Eigen::VectorXd> x,
                                          Eigen::Ref<ekf::RowMatrixXd> P,
                                          const std::vector<TStaticObservation>& obs,
                                          const TUpdateContext& ctx)
{
	TUpdateResult res;
	const Eigen::Vector3d ego = x.head<3>();
	std::vector<int>& idx = m_idx;
	auto& Jx = m_Jx;
	auto& Jf = m_Jf;
	auto& nus = m_nus;
	idx.assign({0, 1, 2});
	Jx.clear();
	Jf.clear();
	nus.clear();
	for (const auto& o : obs)
	{
		const int si = o.index;
		models::Matrix23d J_z_x;
		Eigen::Matrix2d J_z_f;
		const Eigen::Vector2d zhat = models::observeFromSensor(
		    ctx.model, ego, ctx.sensor_pose, Eigen::Vector2d(x[si], x[si + 1]), &J_z_x, &J_z_f);
		const Eigen::Vector2d nu = models::innovation(ctx.model, o.z, zhat);
		if (ctx.jacobians) ctx.jacobians(o.id, ego, J_z_x, J_z_f);
		if (std::isfinite(ctx.gate_threshold))
		{
			const std::vector<int> loc{0, 1, 2, si, si + 1};
			Eigen::Matrix<double, 2, 5> Hi;
			Hi << J_z_x, J_z_f;
			const Eigen::Matrix2d Si = Hi * P(loc, loc) * Hi.transpose() + ctx.R;
			if (nu.dot(Si.ldlt().solve(nu)) > ctx.gate_threshold)
			{
				++res.gated_out;
				continue;
			}
		}
		idx.insert(idx.end(), {si, si + 1});
		Jx.push_back(J_z_x);
		Jf.push_back(J_z_f);
		nus.push_back(nu);
	}
	const Eigen::Index k = Eigen::Index(nus.size());
	res.updates = size_t(k);
	res.nis_dof = size_t(2 * k);
	if (k == 0) return res;
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * k, 3 + 2 * k);
	Eigen::VectorXd nu(2 * k);
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * k, 2 * k);
	for (Eigen::Index j = 0; j < k; ++j)
	{
		H.block<2, 3>(2 * j, 0) = Jx[j];
		H.block<2, 2>(2 * j, 3 + 2 * j) = Jf[j];
		nu.segment<2>(2 * j) = nus[j];
		R.block<2, 2>(2 * j, 2 * j) = ctx.R;
	}
	res.nis = ekf::sparseUpdate(x, P, idx, H, nu, R);
	return res;
}
}  // namespace dynslam::estimator
