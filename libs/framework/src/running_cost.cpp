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
// variables
// ---------------------------------------------------------------------------------------
void CRunningCost::addVariable(const TVarKey& key, const Eigen::VectorXd& value)
{
	if (has(key))
		throw std::invalid_argument("CRunningCost: variable " + toString(key) + " exists");
	if (value.size() == 0 || !value.allFinite())
		throw std::invalid_argument("CRunningCost: value of " + toString(key) +
		                            " empty or not finite");
	m_index[key] = m_keys.size();
	m_keys.push_back(key);
	Eigen::VectorXd v = value;
	const int ai = angleIndex(key.kind, int(v.size()));
	if (ai >= 0) v[ai] = std::remainder(v[ai], 2 * M_PI);
	m_values.push_back(v);
	m_offsets.push_back(m_totalDim);
	m_totalDim += int(v.size());
}

const Eigen::VectorXd& CRunningCost::value(const TVarKey& key) const
{
	const auto it = m_index.find(key);
	if (it == m_index.end()) throw std::out_of_range("CRunningCost: no variable " + toString(key));
	return m_values[it->second];
}

void CRunningCost::setValue(const TVarKey& key, const Eigen::VectorXd& v)
{
	const auto it = m_index.find(key);
	if (it == m_index.end()) throw std::out_of_range("CRunningCost: no variable " + toString(key));
	if (v.size() != m_values[it->second].size() || !v.allFinite())
		throw std::invalid_argument("CRunningCost: bad value for " + toString(key));
	m_values[it->second] = v;
}

int CRunningCost::offset(const TVarKey& key) const
{
	const auto it = m_index.find(key);
	if (it == m_index.end()) throw std::out_of_range("CRunningCost: no variable " + toString(key));
	return m_offsets[it->second];
}

Eigen::VectorXd CRunningCost::stackedValues() const
{
	Eigen::VectorXd x(m_totalDim);
	for (size_t i = 0; i < m_keys.size(); ++i)
		x.segment(m_offsets[i], m_values[i].size()) = m_values[i];
	return x;
}

void CRunningCost::reindex()
{
	m_index.clear();
	m_offsets.assign(m_keys.size(), 0);
	m_totalDim = 0;
	for (size_t i = 0; i < m_keys.size(); ++i)
	{
		m_index[m_keys[i]] = i;
		m_offsets[i] = m_totalDim;
		m_totalDim += int(m_values[i].size());
	}
}

// ---------------------------------------------------------------------------------------
// terms
// ---------------------------------------------------------------------------------------
void CRunningCost::addTerm(const CTermPtr& term)
{
	if (!term) throw std::invalid_argument("CRunningCost::addTerm: null term");
	for (const auto& k : term->keys())
		if (!has(k))
			throw std::invalid_argument("CRunningCost::addTerm: term '" + term->name() +
			                            "' references variable " + toString(k) +
			                            ", which does not exist (add the variable first)");
	// Evaluate once: catches wrong block sizes and non-finite residuals at insertion.
	const TLinearization L = term->linearize(termValues(*term));
	if (!L.r.allFinite() || !L.W.allFinite())
		throw std::invalid_argument("CRunningCost::addTerm: term '" + term->name() +
		                            "' is not finite at the current values");
	for (size_t i = 0; i < term->keys().size(); ++i)
		if (L.J[i].rows() != L.r.size() || L.J[i].cols() != dim(term->keys()[i]))
			throw std::invalid_argument("CRunningCost::addTerm: term '" + term->name() +
			                            "': block size mismatch for " + toString(term->keys()[i]));
	m_terms.push_back(term);
}

bool CRunningCost::removeTerm(const CTermPtr& term)
{
	const auto it = std::find(m_terms.begin(), m_terms.end(), term);
	if (it == m_terms.end()) return false;
	m_terms.erase(it);
	return true;
}

std::vector<Eigen::VectorXd> CRunningCost::termValues(const CTerm& t) const
{
	std::vector<Eigen::VectorXd> x;
	x.reserve(t.keys().size());
	for (const auto& k : t.keys()) x.push_back(value(k));
	return x;
}

double CRunningCost::evaluate() const
{
	double c = 0;
	for (const auto& t : m_terms)
	{
		const TLinearization L = t->linearize(termValues(*t));
		c += L.r.dot(L.W * L.r);
	}
	return c;
}

void CRunningCost::buildNormal(const std::vector<size_t>& termIdx,
                               const std::vector<int>& localOffset, Eigen::MatrixXd& H,
                               Eigen::VectorXd& g, double* cost) const
{
	if (cost) *cost = 0;
	for (size_t ti : termIdx)
	{
		const CTerm& t = *m_terms[ti];
		const TLinearization L = t.linearize(termValues(t));
		if (cost) *cost += L.r.dot(L.W * L.r);
		std::vector<int> off;
		for (const auto& k : t.keys()) off.push_back(localOffset[m_index.at(k)]);
		detail::scatterTerm(
		    t, L, off,
		    [&](int r, int c, const Eigen::MatrixXd& B) { H.block(r, c, B.rows(), B.cols()) += B; },
		    [&](int r, const Eigen::VectorXd& v) { g.segment(r, v.size()) += v; });
	}
}

// ---------------------------------------------------------------------------------------
// Gauss-Newton
// ---------------------------------------------------------------------------------------
void CRunningCost::throwSingular(const Eigen::MatrixXd& Hs, const std::string& where) const
{
	std::ostringstream msg;
	msg << where << ": singular system (J^T J is rank-deficient); unobservable direction in: ";
	const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Hs);
	const Eigen::VectorXd v = es.eigenvectors().col(0);
	std::vector<std::pair<double, size_t>> w;
	for (size_t i = 0; i < m_keys.size(); ++i)
		w.emplace_back(v.segment(m_offsets[i], m_values[i].size()).norm(), i);
	std::sort(w.rbegin(), w.rend());
	for (size_t j = 0; j < w.size() && w[j].first > 0.1 * w[0].first && j < 6; ++j)
		msg << (j ? ", " : "") << toString(m_keys[w[j].second]);
	msg << " (smallest scaled eigenvalue " << es.eigenvalues()[0] << ")";
	throw std::runtime_error(msg.str());
}

void CRunningCost::throwUnconstrained(int idx) const
{
	for (size_t i = 0; i < m_keys.size(); ++i)
		if (idx >= m_offsets[i] && idx < m_offsets[i] + m_values[i].size())
			throw std::runtime_error("CRunningCost::gaussNewtonStep: singular system: variable " +
			                         toString(m_keys[i]) +
			                         " is not constrained by any term (unobservable)");
	throw std::logic_error("unconstrained index");
}

void CRunningCost::solveDense(const std::vector<size_t>& all, const TGaussNewtonOptions& opts,
                              Eigen::VectorXd& g, Eigen::VectorXd& delta,
                              TGaussNewtonResult& res) const
{
	const int n = m_totalDim;
	Eigen::VectorXd s;
	int bad = -1;
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
	buildNormal(all, m_offsets, H, g, &res.cost_before);
	H = 0.5 * (H + H.transpose()).eval();
	const bool scaled = detail::jacobiScale(H.diagonal(), s, bad);
	if (!scaled && !opts.allow_singular) throwUnconstrained(bad);
	const Eigen::MatrixXd Hs = s.asDiagonal() * H * s.asDiagonal();
	const Eigen::LDLT<Eigen::MatrixXd> ldlt(Hs);
	const bool ok = scaled && ldlt.info() == Eigen::Success && ldlt.isPositive() &&
	                ldlt.vectorD().minCoeff() > opts.singular_tol;
	Eigen::MatrixXd HsInv;
	if (ok)
	{
		delta = -(s.asDiagonal() * ldlt.solve(s.asDiagonal() * g));
		if (opts.compute_covariance) HsInv = ldlt.solve(Eigen::MatrixXd::Identity(n, n));
	}
	else if (opts.allow_singular)
	{
		HsInv = psdPseudoInverse(Hs, opts.singular_tol);
		delta = -(s.asDiagonal() * HsInv * (s.asDiagonal() * g));
	}
	else
		throwSingular(Hs, "CRunningCost::gaussNewtonStep");
	if (HsInv.size())
	{
		res.covariance = s.asDiagonal() * HsInv * s.asDiagonal();
		res.covariance = 0.5 * (res.covariance + res.covariance.transpose()).eval();
	}
	res.information = std::move(H);
}

void CRunningCost::solveSparse(const std::vector<size_t>& all, const TGaussNewtonOptions& opts,
                               Eigen::VectorXd& g, Eigen::VectorXd& delta,
                               TGaussNewtonResult& res) const
{
	const int n = m_totalDim;
	Eigen::VectorXd s;
	int bad = -1;
	if (opts.allow_singular)
		throw std::invalid_argument("gaussNewtonStep: allow_singular needs the dense solver");
	std::vector<Eigen::Triplet<double>> trip;
	res.cost_before = 0;
	for (size_t ti : all)
	{
		const CTerm& t = *m_terms[ti];
		const TLinearization L = t.linearize(termValues(t));
		res.cost_before += L.r.dot(L.W * L.r);
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
		    [&](int r, const Eigen::VectorXd& v) { g.segment(r, v.size()) += v; });
	}
	Eigen::SparseMatrix<double> H(n, n);
	H.setFromTriplets(trip.begin(), trip.end());
	if (!detail::jacobiScale(H.diagonal(), s, bad)) throwUnconstrained(bad);
	const Eigen::SparseMatrix<double> Hs = s.asDiagonal() * H * s.asDiagonal();
	Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Hs);
	if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= opts.singular_tol)
	{
		if (n <= 3000) throwSingular(Eigen::MatrixXd(Hs), "CRunningCost::gaussNewtonStep");
		throw std::runtime_error("CRunningCost::gaussNewtonStep: singular sparse system");
	}
	delta = -(s.asDiagonal() * ldlt.solve(Eigen::VectorXd(s.asDiagonal() * g)));
}

TGaussNewtonResult CRunningCost::gaussNewtonStep(const TGaussNewtonOptions& opts)
{
	const int n = m_totalDim;
	if (n == 0) throw std::runtime_error("CRunningCost::gaussNewtonStep: no variables");
	std::vector<size_t> all(m_terms.size());
	for (size_t i = 0; i < all.size(); ++i) all[i] = i;
	const bool sparse = opts.solver == SolverKind::Sparse ||
	                    (opts.solver == SolverKind::Auto && n > opts.sparse_threshold);
	TGaussNewtonResult res;
	res.dense = !sparse;
	Eigen::VectorXd g = Eigen::VectorXd::Zero(n), delta;
	if (!sparse)
		solveDense(all, opts, g, delta, res);
	else
		solveSparse(all, opts, g, delta, res);
	if (!delta.allFinite())
		throw std::runtime_error("CRunningCost::gaussNewtonStep: non-finite step");
	res.max_step = delta.cwiseAbs().maxCoeff();
	res.cost_linear_min = res.cost_before + g.dot(delta);
	for (size_t i = 0; i < m_keys.size(); ++i)
		m_values[i] =
		    blockPlus(m_keys[i].kind, m_values[i], delta.segment(m_offsets[i], m_values[i].size()));
	return res;
}

void CRunningCost::collapseToPrior(const Eigen::MatrixXd& information)
{
	if (information.rows() != m_totalDim || information.cols() != m_totalDim)
		throw std::invalid_argument("collapseToPrior: information size differs from the state");
	std::vector<int> dims;
	for (const auto& v : m_values) dims.push_back(int(v.size()));
	m_terms.clear();
	if (m_keys.empty()) return;
	m_terms.push_back(std::make_shared<CPriorTerm>(m_keys, dims, stackedValues(), information));
}
}  // namespace dynslam::framework
