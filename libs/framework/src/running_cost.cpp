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

namespace dynslam::framework
{
namespace
{
/** Calls add(rowOffset, colOffset, block) for every block J_i^T W J_j of a linearized term and
 * addG(offset, J_i^T W r); offsets are local (-1: block not in the system, skipped). */
void scatterTerm(
	const CTerm& term, const TLinearization& L, const std::vector<int>& off,
	const std::function<void(int, int, const Eigen::MatrixXd&)>& add,
	const std::function<void(int, const Eigen::VectorXd&)>& addG)
{
	const size_t k = term.keys().size();
	const Eigen::VectorXd Wr = L.W * L.r;
	if (const auto* prior = dynamic_cast<const CPriorTerm*>(&term))
	{
		// J_i are selections: H_ij += W_ij, g_i += (W r)_i.
		std::vector<int> po(k, 0);
		for (size_t i = 1; i < k; ++i) po[i] = po[i - 1] + prior->dims()[i - 1];
		for (size_t i = 0; i < k; ++i)
		{
			if (off[i] < 0) continue;
			const int di = prior->dims()[i];
			addG(off[i], Wr.segment(po[i], di));
			for (size_t j = 0; j < k; ++j)
				if (off[j] >= 0)
					add(off[i], off[j], L.W.block(po[i], po[j], di, prior->dims()[j]));
		}
		return;
	}
	std::vector<Eigen::MatrixXd> JtW(k);
	for (size_t i = 0; i < k; ++i)
		if (off[i] >= 0) JtW[i] = L.J[i].transpose() * L.W;
	for (size_t i = 0; i < k; ++i)
	{
		if (off[i] < 0) continue;
		addG(off[i], L.J[i].transpose() * Wr);
		for (size_t j = 0; j < k; ++j)
			if (off[j] >= 0) add(off[i], off[j], JtW[i] * L.J[j]);
	}
}

/** Jacobi scaling s_i = 1/sqrt(H_ii); returns false (and the index) if some H_ii <= 0
 * (then s_i = 1 for it, so a pseudo-inverse can still be taken). */
bool jacobiScale(const Eigen::VectorXd& diag, Eigen::VectorXd& s, int& bad)
{
	s.resize(diag.size());
	bool ok = true;
	for (Eigen::Index i = 0; i < diag.size(); ++i)
	{
		if (!(diag[i] > 0) || !std::isfinite(diag[i]))
		{
			if (ok) bad = int(i);
			ok = false;
			s[i] = 1.0;
			continue;
		}
		s[i] = 1.0 / std::sqrt(diag[i]);
	}
	return ok;
}
}  // namespace

// ---------------------------------------------------------------------------------------
// variables
// ---------------------------------------------------------------------------------------
void CRunningCost::addVariable(const TVarKey& key, const Eigen::VectorXd& value)
{
	if (has(key)) throw std::invalid_argument("CRunningCost: variable " + toString(key) + " exists");
	if (value.size() == 0 || !value.allFinite())
		throw std::invalid_argument("CRunningCost: value of " + toString(key) + " empty or not finite");
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
	if (it == m_index.end())
		throw std::out_of_range("CRunningCost: no variable " + toString(key));
	return m_values[it->second];
}

void CRunningCost::setValue(const TVarKey& key, const Eigen::VectorXd& v)
{
	const auto it = m_index.find(key);
	if (it == m_index.end())
		throw std::out_of_range("CRunningCost: no variable " + toString(key));
	if (v.size() != m_values[it->second].size() || !v.allFinite())
		throw std::invalid_argument("CRunningCost: bad value for " + toString(key));
	m_values[it->second] = v;
}

int CRunningCost::offset(const TVarKey& key) const
{
	const auto it = m_index.find(key);
	if (it == m_index.end())
		throw std::out_of_range("CRunningCost: no variable " + toString(key));
	return m_offsets[it->second];
}

Eigen::VectorXd CRunningCost::stackedValues() const
{
	Eigen::VectorXd x(m_totalDim);
	for (size_t i = 0; i < m_keys.size(); ++i) x.segment(m_offsets[i], m_values[i].size()) = m_values[i];
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
			throw std::invalid_argument(
				"CRunningCost::addTerm: term '" + term->name() + "' references variable " +
				toString(k) + ", which does not exist (add the variable first)");
	// Evaluate once: catches wrong block sizes and non-finite residuals at insertion.
	const TLinearization L = term->linearize(termValues(*term));
	if (!L.r.allFinite() || !L.W.allFinite())
		throw std::invalid_argument(
			"CRunningCost::addTerm: term '" + term->name() + "' is not finite at the current values");
	for (size_t i = 0; i < term->keys().size(); ++i)
		if (L.J[i].rows() != L.r.size() || L.J[i].cols() != dim(term->keys()[i]))
			throw std::invalid_argument(
				"CRunningCost::addTerm: term '" + term->name() + "': block size mismatch for " +
				toString(term->keys()[i]));
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

void CRunningCost::buildNormal(
	const std::vector<size_t>& termIdx, const std::vector<int>& localOffset, Eigen::MatrixXd& H,
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
		scatterTerm(
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
	Eigen::VectorXd g = Eigen::VectorXd::Zero(n), s, delta;
	int bad = -1;
	auto unconstrained = [&](int idx) {
		for (size_t i = 0; i < m_keys.size(); ++i)
			if (idx >= m_offsets[i] && idx < m_offsets[i] + m_values[i].size())
				throw std::runtime_error(
					"CRunningCost::gaussNewtonStep: singular system: variable " +
					toString(m_keys[i]) + " is not constrained by any term (unobservable)");
		throw std::logic_error("unconstrained index");
	};

	if (!sparse)
	{
		Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
		buildNormal(all, m_offsets, H, g, &res.cost_before);
		H = 0.5 * (H + H.transpose()).eval();
		const bool scaled = jacobiScale(H.diagonal(), s, bad);
		if (!scaled && !opts.allow_singular) unconstrained(bad);
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
	else
	{
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
			scatterTerm(
				t, L, off,
				[&](int r, int c, const Eigen::MatrixXd& B) {
					for (Eigen::Index i = 0; i < B.rows(); ++i)
						for (Eigen::Index j = 0; j < B.cols(); ++j)
							if (B(i, j) != 0) trip.emplace_back(r + i, c + j, B(i, j));
				},
				[&](int r, const Eigen::VectorXd& v) { g.segment(r, v.size()) += v; });
		}
		Eigen::SparseMatrix<double> H(n, n);
		H.setFromTriplets(trip.begin(), trip.end());
		if (!jacobiScale(H.diagonal(), s, bad)) unconstrained(bad);
		const Eigen::SparseMatrix<double> Hs = s.asDiagonal() * H * s.asDiagonal();
		Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Hs);
		if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= opts.singular_tol)
		{
			if (n <= 3000) throwSingular(Eigen::MatrixXd(Hs), "CRunningCost::gaussNewtonStep");
			throw std::runtime_error("CRunningCost::gaussNewtonStep: singular sparse system");
		}
		delta = -(s.asDiagonal() * ldlt.solve(Eigen::VectorXd(s.asDiagonal() * g)));
	}
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
	for (size_t ti = 0; ti < m_terms.size(); ++ti)
	{
		bool hit = false;
		for (const auto& k : m_terms[ti]->keys()) hit = hit || mIdx.count(m_index.at(k));
		if (!hit) continue;
		termIdx.push_back(ti);
		for (const auto& k : m_terms[ti]->keys())
			if (!mIdx.count(m_index.at(k))) kIdx.insert(m_index.at(k));
	}
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
	bool ok = jacobiScale(Hmm.diagonal(), s, bad);
	Eigen::LDLT<Eigen::MatrixXd> ldlt;
	if (ok)
	{
		ldlt.compute(s.asDiagonal() * Hmm * s.asDiagonal());
		ok = ldlt.info() == Eigen::Success && ldlt.isPositive() && ldlt.vectorD().minCoeff() > 1e-12;
	}
	if (!ok)
		throw std::runtime_error(
			"CRunningCost::marginalize: the information on {" + names +
			"} is singular (a variable to marginalize is unobservable); drop it instead");
	auto HmmInv = [&](const Eigen::MatrixXd& B) -> Eigen::MatrixXd {
		return s.asDiagonal() * ldlt.solve(s.asDiagonal() * B);
	};
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
		if (!mIdx.count(i))
		{
			keys.push_back(m_keys[i]);
			values.push_back(m_values[i]);
		}
	m_keys.swap(keys);
	m_values.swap(values);
	reindex();
	if (prior) m_terms.push_back(prior);
	return prior;
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
Eigen::MatrixXd CRunningCost::covariance(
	const std::vector<TVarKey>& blocks, const TGaussNewtonOptions& opts) const
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
		if (!jacobiScale(H.diagonal(), s, bad))
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
			scatterTerm(
				t, L, off,
				[&](int r, int c, const Eigen::MatrixXd& B) {
					for (Eigen::Index i = 0; i < B.rows(); ++i)
						for (Eigen::Index j = 0; j < B.cols(); ++j)
							if (B(i, j) != 0) trip.emplace_back(r + i, c + j, B(i, j));
				},
				[](int, const Eigen::VectorXd&) {});
		}
		Eigen::SparseMatrix<double> H(n, n);
		H.setFromTriplets(trip.begin(), trip.end());
		if (!jacobiScale(H.diagonal(), s, bad))
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

void CRunningCost::whitenedSystem(
	Eigen::MatrixXd& J, Eigen::VectorXd& C, const std::vector<size_t>& termIdx) const
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
void projectorMarginal(
	const Eigen::MatrixXd& J_K, const Eigen::MatrixXd& J_M, const Eigen::VectorXd& C,
	Eigen::MatrixXd& Omega_K, Eigen::VectorXd& d_K)
{
	const Eigen::MatrixXd JtJ = J_M.transpose() * J_M;
	const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(J_M.rows(), J_M.rows()) -
							  J_M * JtJ.ldlt().solve(J_M.transpose());
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
