#include <dynslam/estimator/robust_update_engines.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynslam::estimator
{
namespace
{
/// The readings linearised at the prior, as CSparseUpdateEngine does.
struct TLinearised
{
	std::vector<models::Matrix23d> Jx;
	std::vector<Eigen::Matrix2d> Jf;
	std::vector<Eigen::Vector2d> nu;
};

TLinearised linearise(const Eigen::Ref<Eigen::VectorXd>& x,
                      const std::vector<TStaticObservation>& obs, const TUpdateContext& ctx)
{
	TLinearised l;
	const Eigen::Vector3d ego = x.head<3>();
	for (const auto& o : obs)
	{
		models::Matrix23d J_z_x;
		Eigen::Matrix2d J_z_f;
		const Eigen::Vector2d zhat =
		    models::observeFromSensor(ctx.model, ego, ctx.sensor_pose,
		                              Eigen::Vector2d(x[o.index], x[o.index + 1]), &J_z_x, &J_z_f);
		const Eigen::Vector2d nu = models::innovation(ctx.model, o.z, zhat);
		if (ctx.jacobians) ctx.jacobians(o.id, ego, J_z_x, J_z_f);
		l.Jx.push_back(J_z_x);
		l.Jf.push_back(J_z_f);
		l.nu.push_back(nu);
	}
	return l;
}

/// The sparse update with the readings `use` and per-reading noise R / w[j]; returns the NIS.
double weightedUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
                      const std::vector<TStaticObservation>& obs, const TLinearised& l,
                      const std::vector<size_t>& use, const std::vector<double>& w,
                      const Eigen::Matrix2d& R0)
{
	const Eigen::Index k = Eigen::Index(use.size());
	if (k == 0) return 0;
	std::vector<int> idx{0, 1, 2};
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * k, 3 + 2 * k);
	Eigen::VectorXd nu(2 * k);
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * k, 2 * k);
	for (Eigen::Index j = 0; j < k; ++j)
	{
		const size_t i = use[size_t(j)];
		idx.insert(idx.end(), {obs[i].index, obs[i].index + 1});
		H.block<2, 3>(2 * j, 0) = l.Jx[i];
		H.block<2, 2>(2 * j, 3 + 2 * j) = l.Jf[i];
		nu.segment<2>(2 * j) = l.nu[i];
		R.block<2, 2>(2 * j, 2 * j) = w.empty() ? R0 : Eigen::Matrix2d(R0 / w[i]);
	}
	return ekf::sparseUpdate(x, P, idx, H, nu, R);
}

/// Squared Mahalanobis distance of reading i's innovation with its own 2x2 S.
double gateDistance2(const Eigen::Ref<ekf::RowMatrixXd>& P, const TStaticObservation& o,
                     const TLinearised& l, size_t i, const Eigen::Matrix2d& R)
{
	const std::vector<int> loc{0, 1, 2, o.index, o.index + 1};
	Eigen::Matrix<double, 2, 5> Hi;
	Hi << l.Jx[i], l.Jf[i];
	const Eigen::Matrix2d Si = Hi * P(loc, loc) * Hi.transpose() + R;
	return l.nu[i].dot(Si.ldlt().solve(l.nu[i]));
}
}  // namespace

double robustWeight(RobustKernel k, double d, double c)
{
	if (k == RobustKernel::Huber) return d <= c ? 1.0 : c / d;
	const double r = d / c;
	return 1.0 / (1.0 + r * r);
}

CRobustUpdateEngine::CRobustUpdateEngine(RobustKernel kernel, double c, int iterations)
    : m_kernel(kernel), m_c(c), m_maxIterations(iterations)
{
	if (!(c > 0) || !std::isfinite(c))
		throw std::invalid_argument("CRobustUpdateEngine: kernel parameter c = " +
		                            std::to_string(c) + " must be finite and > 0");
	if (iterations < 1)
		throw std::invalid_argument(
		    "CRobustUpdateEngine: iterations = " + std::to_string(iterations) + " must be >= 1");
}

std::string CRobustUpdateEngine::name() const
{
	return m_kernel == RobustKernel::Huber ? "huber" : "cauchy";
}

TUpdateResult CRobustUpdateEngine::update(Eigen::Ref<Eigen::VectorXd> x,
                                          Eigen::Ref<ekf::RowMatrixXd> P,
                                          const std::vector<TStaticObservation>& obs,
                                          const TUpdateContext& ctx)
{
	TUpdateResult res;
	const TLinearised l = linearise(x, obs, ctx);
	std::vector<size_t> all(obs.size());
	for (size_t i = 0; i < all.size(); ++i) all[i] = i;
	m_weights.assign(obs.size(), 1.0);
	m_iterations = 0;
	res.updates = obs.size();
	res.nis_dof = 2 * obs.size();
	if (obs.empty()) return res;
	const Eigen::VectorXd x0 = x;
	const ekf::RowMatrixXd P0 = P;
	const Eigen::LLT<Eigen::Matrix2d> Rllt(ctx.R);
	for (m_iterations = 1;; ++m_iterations)
	{
		x = x0;
		P = P0;
		res.nis = weightedUpdate(x, P, obs, l, all, m_weights, ctx.R);
		if (m_iterations >= m_maxIterations) break;
		double change = 0;
		std::vector<double> w(obs.size());
		for (size_t i = 0; i < obs.size(); ++i)
		{
			const Eigen::Vector3d dEgo = (x - x0).head<3>();
			const Eigen::Vector2d dF = (x - x0).segment<2>(obs[i].index);
			const Eigen::Vector2d r = l.nu[i] - l.Jx[i] * dEgo - l.Jf[i] * dF;
			const double d = Rllt.matrixL().solve(r).norm();
			w[i] = std::max(1e-12, robustWeight(m_kernel, d, m_c));
			change = std::max(change, std::abs(w[i] - m_weights[i]));
		}
		if (change < 1e-9) break;
		m_weights = w;
	}
	return res;
}

CGateRecoveryUpdateEngine::CGateRecoveryUpdateEngine(const TGateRecoveryParams& p) : m_p(p)
{
	if (p.count < 1)
		throw std::invalid_argument("gate_recovery: recovery_count = " + std::to_string(p.count) +
		                            " must be >= 1");
	if (!(p.inflation > 1) || !std::isfinite(p.inflation))
		throw std::invalid_argument("gate_recovery: recovery_inflation = " +
		                            std::to_string(p.inflation) + " must be finite and > 1");
	if (p.min_updates < 0)
		throw std::invalid_argument("gate_recovery: recovery_min_updates = " +
		                            std::to_string(p.min_updates) + " must be >= 0");
}

TUpdateResult CGateRecoveryUpdateEngine::update(Eigen::Ref<Eigen::VectorXd> x,
                                                Eigen::Ref<ekf::RowMatrixXd> P,
                                                const std::vector<TStaticObservation>& obs,
                                                const TUpdateContext& ctx)
{
	if (!std::isfinite(ctx.gate_threshold))
		throw std::invalid_argument("gate_recovery: needs a gate (innovation_gate > 0)");
	TUpdateResult res;
	const TLinearised l = linearise(x, obs, ctx);
	const auto gate = [&](std::vector<size_t>& use)
	{
		use.clear();
		for (size_t i = 0; i < obs.size(); ++i)
			if (gateDistance2(P, obs[i], l, i, ctx.R) <= ctx.gate_threshold) use.push_back(i);
	};
	std::vector<size_t> use;
	gate(use);
	std::vector<bool> accepted(obs.size(), false);
	for (size_t i : use) accepted[i] = true;
	bool trigger = false;
	for (size_t i = 0; i < obs.size(); ++i)
		if (!accepted[i] && m_accepted[obs[i].id] >= m_p.min_updates &&
		    m_rejectedInARow[obs[i].id] + 1 >= m_p.count)
			trigger = true;
	if (trigger)
	{
		const double s = std::sqrt(m_p.inflation);
		P.leftCols<3>() *= s;
		P.topRows<3>() *= s;
		++m_inflations;
		gate(use);
		accepted.assign(obs.size(), false);
		for (size_t i : use) accepted[i] = true;
	}
	for (size_t i = 0; i < obs.size(); ++i)
	{
		if (accepted[i])
		{
			++m_accepted[obs[i].id];
			m_rejectedInARow[obs[i].id] = 0;
		}
		else
			++m_rejectedInARow[obs[i].id];
	}
	res.gated_out = obs.size() - use.size();
	res.updates = use.size();
	res.nis_dof = 2 * use.size();
	res.nis = weightedUpdate(x, P, obs, l, use, {}, ctx.R);
	return res;
}
}  // namespace dynslam::estimator
