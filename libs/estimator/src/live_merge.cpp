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

CLiveMergeDetector::CLiveMergeDetector(const TLiveMergeParams& p) : m_p(p)
{
	if (p.window < 1) throw std::invalid_argument("classify_merge_live_window must be >= 1");
	if (!(p.alpha > 0 && p.alpha < 1))
		throw std::invalid_argument("classify_merge_live_alpha = " + std::to_string(p.alpha) +
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
	const TLiveMergeSample& first = p.samples.front();
	st.drift_chi2 = quadLogDet(s.y - first.y, s.S + first.S).first;
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
}  // namespace dynslam::estimator
