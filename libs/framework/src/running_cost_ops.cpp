#include <dynslam/framework/running_cost.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "running_cost_detail.h"

namespace dynslam::framework
{
// ---------------------------------------------------------------------------------------
// marginalization and drop
// ---------------------------------------------------------------------------------------
std::shared_ptr<CPriorTerm> CRunningCost::marginalize(const std::vector<TVarKey>& M)
{
	std::set<size_t> mIdx;
	for (const auto& k : M)
	{
		const auto it = m_index.find(k);
		if (it == m_index.end())
			throw std::out_of_range("CRunningCost::marginalize: no variable " + toString(k));
		mIdx.insert(it->second);
	}
	if (mIdx.empty()) return nullptr;
	std::vector<size_t> termIdx;
	std::set<size_t> kIdx;
	termsTouching(mIdx, termIdx, kIdx);
	// Local system [K, M].
	std::vector<int> local(m_keys.size(), -1);
	int nK = 0, nM = 0;
	for (size_t i : kIdx)
	{
		local[i] = nK;
		nK += int(m_values[i].size());
	}
	for (size_t i : mIdx)
	{
		local[i] = nK + nM;
		nM += int(m_values[i].size());
	}
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(nK + nM, nK + nM);
	Eigen::VectorXd g = Eigen::VectorXd::Zero(nK + nM);
	buildNormal(termIdx, local, H, g, nullptr);
	H = 0.5 * (H + H.transpose()).eval();

	const Eigen::MatrixXd Hmm = H.bottomRightCorner(nM, nM);
	Eigen::VectorXd s;
	int bad = -1;
	std::string names;
	for (size_t i : mIdx) names += (names.empty() ? "" : ", ") + toString(m_keys[i]);
	bool ok = detail::jacobiScale(Hmm.diagonal(), s, bad);
	Eigen::LDLT<Eigen::MatrixXd> ldlt;
	if (ok)
	{
		ldlt.compute(s.asDiagonal() * Hmm * s.asDiagonal());
		ok =
		    ldlt.info() == Eigen::Success && ldlt.isPositive() && ldlt.vectorD().minCoeff() > 1e-12;
	}
	if (!ok)
		throw std::runtime_error(
		    "CRunningCost::marginalize: the information on {" + names +
		    "} is singular (a variable to marginalize is unobservable); drop it instead");
	auto HmmInv = [&](const Eigen::MatrixXd& B) -> Eigen::MatrixXd
	{ return s.asDiagonal() * ldlt.solve(s.asDiagonal() * B); };
	std::shared_ptr<CPriorTerm> prior;
	if (nK > 0)
	{
		const Eigen::MatrixXd Hkm = H.topRightCorner(nK, nM);
		Eigen::MatrixXd Omega = H.topLeftCorner(nK, nK) - Hkm * HmmInv(Hkm.transpose());
		Omega = 0.5 * (Omega + Omega.transpose()).eval();
		const Eigen::VectorXd gK = g.head(nK) - Hkm * HmmInv(g.tail(nM));
		Eigen::VectorXd d = Eigen::VectorXd::Zero(nK);
		if (gK.cwiseAbs().maxCoeff() > 0) d = -psdPseudoInverse(Omega) * gK;
		std::vector<TVarKey> keys;
		std::vector<int> dims;
		Eigen::VectorXd mean(nK);
		for (size_t i : kIdx)
		{
			keys.push_back(m_keys[i]);
			dims.push_back(int(m_values[i].size()));
			mean.segment(local[i], dims.back()) =
			    blockPlus(m_keys[i].kind, m_values[i], d.segment(local[i], dims.back()));
		}
		prior = std::make_shared<CPriorTerm>(keys, dims, mean, Omega);
	}
	// Remove the terms and the variables, then add the prior.
	eraseTermsAndVariables(termIdx, mIdx);
	if (prior) m_terms.push_back(prior);
	return prior;
}

void CRunningCost::termsTouching(const std::set<size_t>& mIdx, std::vector<size_t>& termIdx,
                                 std::set<size_t>& kIdx) const
{
	for (size_t ti = 0; ti < m_terms.size(); ++ti)
	{
		bool hit = false;
		for (const auto& k : m_terms[ti]->keys()) hit = hit || mIdx.count(m_index.at(k));
		if (!hit) continue;
		termIdx.push_back(ti);
		for (const auto& k : m_terms[ti]->keys())
			if (!mIdx.count(m_index.at(k))) kIdx.insert(m_index.at(k));
	}
}

void CRunningCost::eraseTermsAndVariables(const std::vector<size_t>& termIdx,
                                          const std::set<size_t>& varIdx)
{
	std::vector<CTermPtr> kept;
	size_t q = 0;
	for (size_t ti = 0; ti < m_terms.size(); ++ti)
	{
		if (q < termIdx.size() && termIdx[q] == ti)
		{
			++q;
			continue;
		}
		kept.push_back(m_terms[ti]);
	}
	m_terms.swap(kept);
	std::vector<TVarKey> keys;
	std::vector<Eigen::VectorXd> values;
	for (size_t i = 0; i < m_keys.size(); ++i)
		if (!varIdx.count(i))
		{
			keys.push_back(m_keys[i]);
			values.push_back(m_values[i]);
		}
	m_keys.swap(keys);
	m_values.swap(values);
	reindex();
}

void CRunningCost::drop(const std::vector<TVarKey>& D)
{
	std::set<TVarKey> d;
	for (const auto& k : D)
	{
		if (!has(k)) throw std::out_of_range("CRunningCost::drop: no variable " + toString(k));
		d.insert(k);
	}
	std::vector<CTermPtr> kept;
	for (const auto& t : m_terms)
	{
		bool hit = false;
		for (const auto& k : t->keys()) hit = hit || d.count(k);
		if (!hit) kept.push_back(t);
	}
	m_terms.swap(kept);
	std::vector<TVarKey> keys;
	std::vector<Eigen::VectorXd> values;
	for (size_t i = 0; i < m_keys.size(); ++i)
		if (!d.count(m_keys[i]))
		{
			keys.push_back(m_keys[i]);
			values.push_back(m_values[i]);
		}
	m_keys.swap(keys);
	m_values.swap(values);
	reindex();
}

// ---------------------------------------------------------------------------------------
// covariance and whitened system
// ---------------------------------------------------------------------------------------
Eigen::MatrixXd CRunningCost::covariance(const std::vector<TVarKey>& blocks,
                                         const TGaussNewtonOptions& opts) const
{
	const int n = m_totalDim;
	std::vector<int> cols;
	for (const auto& k : blocks)
		for (int i = 0; i < dim(k); ++i) cols.push_back(offset(k) + i);
	const int m = int(cols.size());
	Eigen::MatrixXd E = Eigen::MatrixXd::Zero(n, m);
	for (int j = 0; j < m; ++j) E(cols[j], j) = 1;
	std::vector<size_t> all(m_terms.size());
	for (size_t i = 0; i < all.size(); ++i) all[i] = i;
	const bool sparse = opts.solver == SolverKind::Sparse ||
	                    (opts.solver == SolverKind::Auto && n > opts.sparse_threshold);
	Eigen::VectorXd s;
	int bad = -1;
	Eigen::MatrixXd X;
	if (!sparse)
	{
		Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
		Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
		buildNormal(all, m_offsets, H, g, nullptr);
		H = 0.5 * (H + H.transpose()).eval();
		if (!detail::jacobiScale(H.diagonal(), s, bad))
			throw std::runtime_error("CRunningCost::covariance: singular (unconstrained variable)");
		const Eigen::MatrixXd Hs = s.asDiagonal() * H * s.asDiagonal();
		const Eigen::LDLT<Eigen::MatrixXd> ldlt(Hs);
		if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
		    ldlt.vectorD().minCoeff() <= opts.singular_tol)
			throwSingular(Hs, "CRunningCost::covariance");
		X = s.asDiagonal() * ldlt.solve(s.asDiagonal() * E);
	}
	else
	{
		std::vector<Eigen::Triplet<double>> trip;
		for (size_t ti : all)
		{
			const CTerm& t = *m_terms[ti];
			const TLinearization L = t.linearize(termValues(t));
			std::vector<int> off;
			for (const auto& k : t.keys()) off.push_back(m_offsets[m_index.at(k)]);
			detail::scatterTerm(
			    t, L, off,
			    [&](int r, int c, const Eigen::MatrixXd& B)
			    {
				    for (Eigen::Index i = 0; i < B.rows(); ++i)
					    for (Eigen::Index j = 0; j < B.cols(); ++j)
						    if (B(i, j) != 0) trip.emplace_back(r + i, c + j, B(i, j));
			    },
			    [](int, const Eigen::VectorXd&) {});
		}
		Eigen::SparseMatrix<double> H(n, n);
		H.setFromTriplets(trip.begin(), trip.end());
		if (!detail::jacobiScale(H.diagonal(), s, bad))
			throw std::runtime_error("CRunningCost::covariance: singular (unconstrained variable)");
		const Eigen::SparseMatrix<double> Hs = s.asDiagonal() * H * s.asDiagonal();
		Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Hs);
		if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= opts.singular_tol)
			throw std::runtime_error("CRunningCost::covariance: singular sparse system");
		X = s.asDiagonal() * ldlt.solve(Eigen::MatrixXd(s.asDiagonal() * E));
	}
	Eigen::MatrixXd C(m, m);
	for (int i = 0; i < m; ++i) C.row(i) = X.row(cols[i]);
	return 0.5 * (C + C.transpose());
}

void CRunningCost::whitenedSystem(Eigen::MatrixXd& J, Eigen::VectorXd& C,
                                  const std::vector<size_t>& termIdx) const
{
	std::vector<size_t> idx = termIdx;
	if (idx.empty())
		for (size_t i = 0; i < m_terms.size(); ++i) idx.push_back(i);
	std::vector<Eigen::MatrixXd> Js;
	std::vector<Eigen::VectorXd> Cs;
	int rows = 0;
	for (size_t ti : idx)
	{
		const CTerm& t = *m_terms.at(ti);
		const TLinearization L = t.linearize(termValues(t));
		// W = S^T S
		const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (L.W + L.W.transpose()));
		const Eigen::VectorXd ev = es.eigenvalues().cwiseMax(0).cwiseSqrt();
		const Eigen::MatrixXd S = ev.asDiagonal() * es.eigenvectors().transpose();
		Eigen::MatrixXd Jt = Eigen::MatrixXd::Zero(L.r.size(), m_totalDim);
		for (size_t i = 0; i < t.keys().size(); ++i)
			Jt.middleCols(offset(t.keys()[i]), L.J[i].cols()) += S * L.J[i];
		Js.push_back(Jt);
		Cs.push_back(S * L.r);
		rows += int(L.r.size());
	}
	J.resize(rows, m_totalDim);
	C.resize(rows);
	int r = 0;
	for (size_t i = 0; i < Js.size(); ++i)
	{
		J.middleRows(r, Js[i].rows()) = Js[i];
		C.segment(r, Cs[i].size()) = Cs[i];
		r += int(Cs[i].size());
	}
}

// ---------------------------------------------------------------------------------------
void projectorMarginal(const Eigen::MatrixXd& J_K, const Eigen::MatrixXd& J_M,
                       const Eigen::VectorXd& C, Eigen::MatrixXd& Omega_K, Eigen::VectorXd& d_K)
{
	const Eigen::MatrixXd JtJ = J_M.transpose() * J_M;
	const Eigen::MatrixXd P =
	    Eigen::MatrixXd::Identity(J_M.rows(), J_M.rows()) - J_M * JtJ.ldlt().solve(J_M.transpose());
	Omega_K = J_K.transpose() * P * J_K;
	Omega_K = 0.5 * (Omega_K + Omega_K.transpose()).eval();
	d_K = -psdPseudoInverse(Omega_K) * (J_K.transpose() * P * C);
}

Eigen::MatrixXd psdPseudoInverse(const Eigen::MatrixXd& A, double tol)
{
	const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()));
	const Eigen::VectorXd& ev = es.eigenvalues();
	const double cut = tol * std::max(ev.cwiseAbs().maxCoeff(), 1e-300);
	Eigen::VectorXd inv = Eigen::VectorXd::Zero(ev.size());
	for (Eigen::Index i = 0; i < ev.size(); ++i)
		if (ev[i] > cut) inv[i] = 1.0 / ev[i];
	return es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose();
}
}  // namespace dynslam::framework
