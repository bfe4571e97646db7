#include <dynslam/core/models/assignment.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace dynslam::models
{
namespace
{
/** Rows <= columns, every entry finite. Returns the column of each row (all assigned). */
std::vector<int> solveDense(const Eigen::MatrixXd& a)
{
	const int n = int(a.rows()), m = int(a.cols());
	const double inf = std::numeric_limits<double>::infinity();
	// 1-based potentials u (rows), v (columns); p[j] = row assigned to column j (0: none)
	std::vector<double> u(size_t(n) + 1, 0), v(size_t(m) + 1, 0);
	std::vector<int> p(size_t(m) + 1, 0), way(size_t(m) + 1, 0);
	for (int i = 1; i <= n; ++i)
	{
		p[0] = i;
		int j0 = 0;
		std::vector<double> minv(size_t(m) + 1, inf);
		std::vector<char> used(size_t(m) + 1, 0);
		do
		{
			used[size_t(j0)] = 1;
			const int i0 = p[size_t(j0)];
			double delta = inf;
			int j1 = 0;
			for (int j = 1; j <= m; ++j)
			{
				if (used[size_t(j)]) continue;
				const double cur = a(i0 - 1, j - 1) - u[size_t(i0)] - v[size_t(j)];
				if (cur < minv[size_t(j)])
				{
					minv[size_t(j)] = cur;
					way[size_t(j)] = j0;
				}
				if (minv[size_t(j)] < delta)
				{
					delta = minv[size_t(j)];
					j1 = j;
				}
			}
			for (int j = 0; j <= m; ++j)
				if (used[size_t(j)])
				{
					u[size_t(p[size_t(j)])] += delta;
					v[size_t(j)] -= delta;
				}
				else
					minv[size_t(j)] -= delta;
			j0 = j1;
		} while (p[size_t(j0)] != 0);
		do
		{
			const int j1 = way[size_t(j0)];
			p[size_t(j0)] = p[size_t(j1)];
			j0 = j1;
		} while (j0 != 0);
	}
	std::vector<int> col(size_t(n), -1);
	for (int j = 1; j <= m; ++j)
		if (p[size_t(j)] > 0) col[size_t(p[size_t(j)] - 1)] = j - 1;
	return col;
}
}  // namespace

std::vector<int> solveAssignment(const Eigen::MatrixXd& cost)
{
	const long n = cost.rows(), m = cost.cols();
	std::vector<int> out(size_t(n), -1);
	if (n == 0 || m == 0) return out;
	// Forbidden pairs get a cost larger than any sum of allowed ones, so that the optimum uses
	// as few of them as possible (= as many allowed pairs as possible), then the least cost.
	double total = 0;
	for (long i = 0; i < n; ++i)
		for (long j = 0; j < m; ++j)
		{
			const double c = cost(i, j);
			if (c == -std::numeric_limits<double>::infinity())
				throw std::invalid_argument("solveAssignment: a cost of -infinity");
			if (std::isfinite(c)) total += std::abs(c);
		}
	const double big = 2 * total + 1;
	Eigen::MatrixXd a(n, m);
	for (long i = 0; i < n; ++i)
		for (long j = 0; j < m; ++j) a(i, j) = std::isfinite(cost(i, j)) ? cost(i, j) : big;
	const bool transposed = n > m;
	const std::vector<int> col = solveDense(transposed ? Eigen::MatrixXd(a.transpose()) : a);
	for (size_t r = 0; r < col.size(); ++r)
	{
		const int i = transposed ? col[r] : int(r);
		const int j = transposed ? int(r) : col[r];
		if (i >= 0 && j >= 0 && std::isfinite(cost(i, j))) out[size_t(i)] = j;
	}
	return out;
}
}  // namespace dynslam::models
