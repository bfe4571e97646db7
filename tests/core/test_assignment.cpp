/** models::solveAssignment (assignment.h): hand-checked optima, rectangular shapes, forbidden
 * pairs (most pairs first, then least cost) and a brute-force comparison on random matrices. */
#include <dynslam/core/models/assignment.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

using dynslam::models::solveAssignment;

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

/** (number of allowed pairs, their total cost) of an assignment. */
std::pair<int, double> score(const Eigen::MatrixXd& c, const std::vector<int>& a)
{
	int n = 0;
	double s = 0;
	std::vector<int> seen;
	for (size_t i = 0; i < a.size(); ++i)
	{
		if (a[i] < 0) continue;
		EXPECT_TRUE(std::isfinite(c(long(i), a[i]))) << "forbidden pair returned";
		EXPECT_EQ(std::count(seen.begin(), seen.end(), a[i]), 0) << "column used twice";
		seen.push_back(a[i]);
		++n;
		s += c(long(i), a[i]);
	}
	return {n, s};
}

/** Best (max pairs, then min cost) over every injective map rows -> columns (rows <= cols). */
std::pair<int, double> bruteForce(const Eigen::MatrixXd& c)
{
	std::vector<int> cols(size_t(c.cols()));
	std::iota(cols.begin(), cols.end(), 0);
	std::pair<int, double> best{-1, 0};
	do
	{
		int n = 0;
		double s = 0;
		for (long i = 0; i < c.rows(); ++i)
			if (std::isfinite(c(i, cols[size_t(i)])))
			{
				++n;
				s += c(i, cols[size_t(i)]);
			}
		if (n > best.first || (n == best.first && s < best.second)) best = {n, s};
	} while (std::next_permutation(cols.begin(), cols.end()));
	return best;
}
}  // namespace

TEST(Hungarian, SquareHandChecked)
{
	// the six permutations cost 6 (diag), 7, 5 (0-1, 1-0, 2-2), 6, 11, 7: the optimum is 5
	Eigen::MatrixXd c(3, 3);
	c << 4, 1, 3, 2, 0, 5, 3, 2, 2;
	EXPECT_EQ(solveAssignment(c), (std::vector<int>{1, 0, 2}));
}

TEST(Hungarian, RectangularBothWays)
{
	// 2 rows, 3 columns: row 0 -> 2 (1), row 1 -> 0 (2): 3, the best of the six maps
	Eigen::MatrixXd c(2, 3);
	c << 5, 4, 1, 2, 3, 1.5;
	EXPECT_EQ(solveAssignment(c), (std::vector<int>{2, 0}));
	// transposed: 3 rows, 2 columns; the row left over is -1
	EXPECT_EQ(solveAssignment(c.transpose()), (std::vector<int>{1, -1, 0}));
	EXPECT_TRUE(solveAssignment(Eigen::MatrixXd(0, 3)).empty());
	EXPECT_EQ(solveAssignment(Eigen::MatrixXd(2, 0)), (std::vector<int>{-1, -1}));
}

TEST(Hungarian, MostAllowedPairsFirst)
{
	// row 1 can only take column 0. Least cost alone would be {row 1 -> 0} (0.5) or
	// {row 0 -> 0} (1); two pairs (10 + 0.5) win because forbidden pairs are not matches.
	Eigen::MatrixXd c(2, 2);
	c << 1, 10, 0.5, kInf;
	EXPECT_EQ(solveAssignment(c), (std::vector<int>{1, 0}));
	c << kInf, kInf, kInf, std::numeric_limits<double>::quiet_NaN();
	EXPECT_EQ(solveAssignment(c), (std::vector<int>{-1, -1}));
	c << 1, -kInf, 0, 0;
	EXPECT_THROW(solveAssignment(c), std::invalid_argument);
}

TEST(Hungarian, AgreesWithBruteForce)
{
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> U(-2, 5);
	std::bernoulli_distribution forbid(0.3);
	for (int trial = 0; trial < 300; ++trial)
	{
		const long n = 1 + trial % 5, m = n + (trial / 5) % 3;
		Eigen::MatrixXd c(n, m);
		for (long i = 0; i < n; ++i)
			for (long j = 0; j < m; ++j) c(i, j) = forbid(rng) ? kInf : U(rng);
		const auto best = bruteForce(c);
		const auto got = score(c, solveAssignment(c));
		ASSERT_EQ(got.first, best.first) << "trial " << trial;
		ASSERT_NEAR(got.second, best.second, 1e-9) << "trial " << trial;
		const Eigen::MatrixXd ct = c.transpose();  // more rows than columns
		const auto gotT = score(ct, solveAssignment(ct));
		ASSERT_EQ(gotT.first, best.first) << "trial " << trial << " transposed";
		ASSERT_NEAR(gotT.second, best.second, 1e-9) << "trial " << trial << " transposed";
	}
}
