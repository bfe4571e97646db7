#include <dynslam/estimator/state_helper.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <stdexcept>
#include <string>

namespace dynslam::estimator::state
{
void propagate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
               const std::vector<int>& idx, const Eigen::VectorXd& f, const Eigen::MatrixXd& F,
               const Eigen::MatrixXd& Q)
{
	const Eigen::Index k = Eigen::Index(idx.size());
	if (f.size() != k || F.rows() != k || F.cols() != k || Q.rows() != k || Q.cols() != k)
		throw std::invalid_argument("state::propagate: f, F, Q must match " + std::to_string(k) +
		                            " entries");
	ekf::predictSubset(x, P, idx, f, F, Q);
}

TUpdateResult update(IUpdateEngine& engine, Eigen::Ref<Eigen::VectorXd> x,
                     Eigen::Ref<ekf::RowMatrixXd> P, const std::vector<TStaticObservation>& obs,
                     const TUpdateContext& ctx)
{
	return engine.update(x, P, obs, ctx);
}

void augment(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout, const TBlock& block,
             const Eigen::VectorXd& g, const std::vector<int>& in, const Eigen::MatrixXd& J,
             const Eigen::MatrixXd& R)
{
	const Eigen::Index d = block.dim, n = x.size();
	if (g.size() != d || J.rows() != d || J.cols() != Eigen::Index(in.size()) || R.rows() != d ||
	    R.cols() != d || P.rows() != n || P.cols() != n || n != layout.storageDim())
		throw std::invalid_argument("state::augment: sizes do not match (block of " +
		                            std::to_string(d) + " entries)");
	const Eigen::Index w = 2 * block.slots();             // with the pad
	const Eigen::MatrixXd cross = J * P(in, Eigen::all);  // d x n
	Eigen::MatrixXd cov = J * P(in, in) * J.transpose() + R;
	cov = 0.5 * (cov + cov.transpose()).eval();
	x.conservativeResize(n + w);
	x.tail(w).setZero();
	x.segment(n, d) = g;
	P.conservativeResize(n + w, n + w);
	P.bottomRows(w).setZero();
	P.rightCols(w).setZero();
	P.block(n, 0, d, n) = cross;
	P.block(0, n, n, d) = cross.transpose();
	P.block(n, n, d, d) = cov;
	for (Eigen::Index i = d; i < w; ++i) P(n + i, n + i) = 1.0;  // the pad
	layout.append(block);
}

void marginalize(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout,
                 const std::vector<bool>& remove)
{
	if (remove.size() != layout.size() || x.size() != layout.storageDim())
		throw std::invalid_argument("state::marginalize: one flag per block of the layout");
	const std::vector<int> keep = layout.keptStorage(remove);
	x = x(keep).eval();
	P = P(keep, keep).eval();
	layout.removeBlocks(remove);
}

void replace(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
             const std::vector<int>& in, const std::vector<int>& out, const Eigen::VectorXd& g,
             const Eigen::MatrixXd& J)
{
	const Eigen::Index o = Eigen::Index(out.size());
	if (g.size() != o || J.rows() != o || J.cols() != Eigen::Index(in.size()))
		throw std::invalid_argument("state::replace: g and J must match |out| x |in|");
	// B = P T^T on the columns out: P[:, in] J^T (the other columns of P T^T are P's).
	const Eigen::MatrixXd B = P(Eigen::all, in) * J.transpose();  // n x o
	Eigen::MatrixXd C = J * B(in, Eigen::all);                    // T P T^T on (out, out)
	C = 0.5 * (C + C.transpose()).eval();
	P(Eigen::all, out) = B;
	P(out, Eigen::all) = B.transpose();
	P(out, out) = C;
	x(out) = g;
}

void condition(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
               const std::vector<int>& a, const std::vector<int>& b)
{
	const Eigen::Index n = x.size(), k = Eigen::Index(a.size());
	const auto inRange = [n](int i) { return i >= 0 && i < n; };
	if (k == 0 || b.size() != a.size() || P.rows() != n || P.cols() != n ||
	    !std::all_of(a.begin(), a.end(), inRange) || !std::all_of(b.begin(), b.end(), inRange))
		throw std::invalid_argument("state::condition: sizes do not match (" +
		                            std::to_string(a.size()) + " and " + std::to_string(b.size()) +
		                            " entries of " + std::to_string(n) + ")");
	for (const int i : a)
		if (std::find(b.begin(), b.end(), i) != b.end())
			throw std::invalid_argument("state::condition: a and b overlap");
	const Eigen::MatrixXd A = P(Eigen::all, a) - P(Eigen::all, b);  // P H^T, n x k
	const Eigen::MatrixXd S = A(a, Eigen::all) - A(b, Eigen::all);  // H P H^T
	const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (S + S.transpose()));
	if (llt.info() != Eigen::Success)
		throw std::runtime_error(
		    "state::condition: the covariance of the difference is not positive definite");
	const Eigen::VectorXd d = x(a) - x(b);
	x.noalias() -= A * llt.solve(d);
	const Eigen::MatrixXd Kt = llt.solve(A.transpose());  // (A S^-1)^T, k x n
	// P - A S^-1 A^T, written symmetric: the upper triangle computed, mirrored.
	for (Eigen::Index r = 0; r < n; ++r)
		for (Eigen::Index c = r; c < n; ++c)
		{
			const double v = P(r, c) - A.row(r).dot(Kt.col(c));
			P(r, c) = v;
			P(c, r) = v;
		}
}
}  // namespace dynslam::estimator::state
