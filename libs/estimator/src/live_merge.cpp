#include <dynslam/estimator/classify_evidence.h>
#include <dynslam/estimator/live_merge.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace dynslam::estimator
{
namespace
{
/** x^T A^-1 x and log det A by Cholesky (A symmetric positive definite). */
std::pair<double, double> quadLogDet(const Eigen::VectorXd& x, const Eigen::MatrixXd& A)
{
	const Eigen::LLT<Eigen::MatrixXd> llt(A);
	if (llt.info() != Eigen::Success)
		throw std::runtime_error("CLiveMergeDetector: covariance not positive definite");
	const Eigen::VectorXd u = llt.matrixL().solve(x);
	return {u.squaredNorm(), 2 * llt.matrixLLT().diagonal().array().log().sum()};
}
}  // namespace

double CLiveMergeDetector::trendChi2(const std::deque<TLiveMergeSample>& samples)
{
	// y_i = a + b t_i + e_i, e_i ~ N(0, S_i) independent: the weighted least-squares slope b and
	// its chi-square b^T Cov(b)^-1 b (the generalised likelihood ratio of b != 0).
	if (samples.size() < 3) return 0;
	const Eigen::Index n = samples.front().y.size();
	double t0 = 0;
	for (const TLiveMergeSample& s : samples) t0 += s.step;
	t0 /= double(samples.size());
	Eigen::MatrixXd N = Eigen::MatrixXd::Zero(2 * n, 2 * n);
	Eigen::VectorXd r = Eigen::VectorXd::Zero(2 * n);
	for (const TLiveMergeSample& s : samples)
	{
		const double t = s.step - t0;
		const Eigen::MatrixXd W = s.S.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
		N.topLeftCorner(n, n) += W;
		N.topRightCorner(n, n) += t * W;
		N.bottomRightCorner(n, n) += t * t * W;
		r.head(n) += W * s.y;
		r.tail(n) += t * W * s.y;
	}
	N.bottomLeftCorner(n, n) = N.topRightCorner(n, n).transpose();
	const Eigen::MatrixXd Ninv = N.ldlt().solve(Eigen::MatrixXd::Identity(2 * n, 2 * n));
	const Eigen::VectorXd b = (Ninv * r).tail(n);
	return b.dot(Ninv.bottomRightCorner(n, n).ldlt().solve(b));
}

CLiveMergeDetector::CLiveMergeDetector(const TLiveMergeParams& p) : m_p(p)
{
	if (p.window < 1) throw std::invalid_argument("classify_merge_live_window must be >= 1");
	if (!(p.alpha > 0 && p.alpha < 1))
		throw std::invalid_argument("live merge alpha = " + std::to_string(p.alpha) +
		                            ": must be a probability in (0, 1)");
}

double CLiveMergeDetector::incrementLlr(const Eigen::VectorXd& delta, const Eigen::MatrixXd& C,
                                        double spread2)
{
	const auto [q0, l0] = quadLogDet(delta, C);
	Eigen::MatrixXd C1 = C;
	C1.diagonal().array() += spread2;
	const auto [q1, l1] = quadLogDet(delta, C1);
	return -0.5 * (q0 + l0) + 0.5 * (q1 + l1);
}

TLiveMergeStats CLiveMergeDetector::observe(int32_t a, int32_t b, const TLiveMergeSample& s)
{
	TPair& p = m_pairs[{a, b}];
	if (!p.samples.empty() &&
	    (p.samples.back().y.size() != s.y.size() || p.samples.back().step >= s.step))
	{
		p.samples.clear();
		p.llr.clear();
	}
	if (!p.samples.empty())
	{
		const TLiveMergeSample& prev = p.samples.back();
		const double g = s.step - prev.step;
		p.llr.push_back(
		    incrementLlr(s.y - prev.y, s.S + prev.S, m_p.motion_std * m_p.motion_std * g));
	}
	p.samples.push_back(s);
	while (int(p.llr.size()) > m_p.window)
	{
		p.llr.pop_front();
		p.samples.pop_front();
	}
	TLiveMergeStats st;
	st.increments = int(p.llr.size());
	st.llr = std::accumulate(p.llr.begin(), p.llr.end(), 0.0);
	st.drift_chi2 = trendChi2(p.samples);
	if (st.increments < m_p.window) return st;
	const double upper = std::log((1 - m_p.beta) / m_p.alpha);
	const int dof = int(s.y.size());
	st.rigid = st.llr >= upper && st.drift_chi2 <= chiSquareQuantile(m_p.rigid_prob, dof) &&
	           (s.vel_dof == 0 || s.vel_chi2 <= chiSquareQuantile(m_p.rigid_prob, s.vel_dof));
	return st;
}

void CLiveMergeDetector::prune(int step, int keep)
{
	for (auto it = m_pairs.begin(); it != m_pairs.end();)
		if (it->second.samples.empty() || it->second.samples.back().step < step - keep)
			it = m_pairs.erase(it);
		else
			++it;
}

std::unique_ptr<CLiveMergeDetector> makeLiveMergeDetector(const TClassifyParams& c,
                                                          bool objectCentric)
{
	if (!c.merge_live) return nullptr;
	const int w = c.merge_live_window > 0 ? c.merge_live_window : objectCentric ? 5 : 20;
	return std::make_unique<CLiveMergeDetector>(
	    TLiveMergeParams{w, TLiveMergeParams().alpha, c.beta, c.motion_std, c.group_prob});
}
}  // namespace dynslam::estimator
