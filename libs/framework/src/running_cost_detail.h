#pragma once
/** Internal helpers of CRunningCost shared by its translation units (not installed API). */
#include <dynslam/framework/running_cost.h>

#include <cmath>
#include <functional>

namespace dynslam::framework
{
namespace detail
{
/** Calls add(rowOffset, colOffset, block) for every block J_i^T W J_j of a linearized term and
 * addG(offset, J_i^T W r); offsets are local (-1: block not in the system, skipped). */
inline void scatterTerm(const CTerm& term, const TLinearization& L, const std::vector<int>& off,
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
				if (off[j] >= 0) add(off[i], off[j], L.W.block(po[i], po[j], di, prior->dims()[j]));
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
inline bool jacobiScale(const Eigen::VectorXd& diag, Eigen::VectorXd& s, int& bad)
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
}  // namespace detail
}  // namespace dynslam::framework
