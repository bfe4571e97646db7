#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/core/models/se2.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dynslam::models
{
TModeMixture mixModes(const std::vector<Eigen::VectorXd>& s_j,
                      const std::vector<Eigen::MatrixXd>& F_j,
                      const std::vector<Eigen::MatrixXd>& Q_j, const Eigen::VectorXd& w,
                      const Eigen::MatrixXd& P_ss, int angleIdx)
{
	const size_t M = s_j.size();
	if (M == 0 || F_j.size() != M || Q_j.size() != M || size_t(w.size()) != M)
		throw std::invalid_argument("mixModes: one s_j, F_j, Q_j and weight per mode");
	const Eigen::Index n = s_j.front().size();
	if (P_ss.rows() != n || P_ss.cols() != n)
		throw std::invalid_argument("mixModes: P_ss must be " + std::to_string(n) + "x" +
		                            std::to_string(n));
	if ((w.array() < 0).any() || std::abs(w.sum() - 1.0) > 1e-9)
		throw std::invalid_argument("mixModes: weights must be >= 0 and sum to 1");
	for (size_t j = 0; j < M; ++j)
		if (s_j[j].size() != n || F_j[j].rows() != n || F_j[j].cols() != n || Q_j[j].rows() != n ||
		    Q_j[j].cols() != n)
			throw std::invalid_argument("mixModes: mode " + std::to_string(j) + " has wrong sizes");
	// The mean: angles averaged as offsets from mode 0 (no jump across +-pi).
	const auto diff = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b)
	{
		Eigen::VectorXd d = a - b;
		if (angleIdx >= 0) d[angleIdx] = wrapToPi(d[angleIdx]);
		return d;
	};
	TModeMixture out;
	out.s = s_j.front();
	Eigen::VectorXd offset = Eigen::VectorXd::Zero(n);
	out.F = Eigen::MatrixXd::Zero(n, n);
	for (size_t j = 0; j < M; ++j)
	{
		offset += w[Eigen::Index(j)] * diff(s_j[j], s_j.front());
		out.F += w[Eigen::Index(j)] * F_j[j];
	}
	out.s += offset;
	if (angleIdx >= 0) out.s[angleIdx] = wrapToPi(out.s[angleIdx]);
	out.Q_eff = Eigen::MatrixXd::Zero(n, n);
	for (size_t j = 0; j < M; ++j)
	{
		const Eigen::MatrixXd dF = F_j[j] - out.F;
		const Eigen::VectorXd d = diff(s_j[j], out.s);
		out.Q_eff += w[Eigen::Index(j)] * (dF * P_ss * dF.transpose() + Q_j[j] + d * d.transpose());
	}
	out.Q_eff = (0.5 * (out.Q_eff + out.Q_eff.transpose())).eval();
	return out;
}

Eigen::MatrixXd uniformSwitching(int M, double p_switch)
{
	if (M < 2) throw std::invalid_argument("uniformSwitching: needs at least 2 modes");
	if (!(p_switch >= 0 && p_switch < 1))
		throw std::invalid_argument("uniformSwitching: p_switch = " + std::to_string(p_switch) +
		                            ": must be in [0, 1)");
	Eigen::MatrixXd Pi = Eigen::MatrixXd::Constant(M, M, p_switch / double(M - 1));
	Pi.diagonal().setConstant(1.0 - p_switch);
	return Pi;
}

Eigen::VectorXd modePosterior(const Eigen::VectorXd& mu, const Eigen::MatrixXd& Pi,
                              const Eigen::VectorXd& logL)
{
	const Eigen::Index M = mu.size();
	if (Pi.rows() != M || Pi.cols() != M || (logL.size() != 0 && logL.size() != M))
		throw std::invalid_argument("modePosterior: mu (M), Pi (M x M) and logL (M or empty)");
	const Eigen::VectorXd prior = Pi.transpose() * mu;
	if (logL.size() == 0) return prior;
	double best = -std::numeric_limits<double>::infinity();
	for (Eigen::Index j = 0; j < M; ++j)
		if (prior[j] > 0) best = std::max(best, logL[j] + std::log(prior[j]));
	if (!std::isfinite(best)) return prior;
	Eigen::VectorXd post(M);
	for (Eigen::Index j = 0; j < M; ++j)
		post[j] = prior[j] > 0 ? std::exp(logL[j] + std::log(prior[j]) - best) : 0.0;
	return post / post.sum();
}

Eigen::VectorXd prunedWeights(const Eigen::VectorXd& mu)
{
	const Eigen::VectorXd w = (mu.array() < kModePruneProbability).select(0.0, mu);
	return w.sum() > 0 ? Eigen::VectorXd(w / w.sum()) : mu;
}

double gaussianLogLikelihood(const Eigen::VectorXd& nu, const Eigen::MatrixXd& S)
{
	const Eigen::LLT<Eigen::MatrixXd> llt(S);
	if (llt.info() != Eigen::Success)
		throw std::runtime_error("gaussianLogLikelihood: S is not positive definite");
	const Eigen::VectorXd y = llt.matrixL().solve(nu);
	const double logDet = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
	return -0.5 * (y.squaredNorm() + logDet);
}

double predictedReadingsLogLikelihood(const Eigen::MatrixXd& P_e, Eigen::Index sOffset,
                                      const Eigen::MatrixXd& F, const Eigen::MatrixXd& Q,
                                      const Eigen::MatrixXd& H, const Eigen::VectorXd& nu,
                                      const Eigen::MatrixXd& R)
{
	const Eigen::Index n = P_e.rows(), ns = F.rows();
	if (P_e.cols() != n || F.cols() != ns || Q.rows() != ns || Q.cols() != ns || sOffset < 0 ||
	    sOffset + ns > n || H.cols() != n || H.rows() != nu.size() || R.rows() != nu.size() ||
	    R.cols() != nu.size())
		throw std::invalid_argument("predictedReadingsLogLikelihood: sizes do not match");
	Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n);
	T.block(sOffset, sOffset, ns, ns) = F;
	Eigen::MatrixXd P = T * P_e * T.transpose();
	P.block(sOffset, sOffset, ns, ns) += Q;
	return gaussianLogLikelihood(nu, H * P * H.transpose() + R);
}
}  // namespace dynslam::models
