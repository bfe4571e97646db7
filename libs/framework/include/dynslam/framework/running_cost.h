#pragma once
/** @file running_cost.h
 * The running cost of the unifying framework (paper Section II, Appendix A): variables (typed
 * blocks with a current value, the linearization point x*) and a sum of residual terms, with
 * the three operations of the framework:
 *  - gaussNewtonStep(): Sigma <- (J^T J)^+, mu <- x* - (J^T J)^+ J^T C(x*) (whitened J, C);
 *    the normal equations H = J^T J are built block-sparse from the terms and solved with
 *    Eigen's LDLT (dense) or SimplicialLDLT (sparse);
 *  - marginalize(M): the terms touching M are linearized and replaced by a Gaussian prior on
 *    their other variables (Schur complement of the information; equal to the paper's
 *    J_K^T (I - J_M (J_M^T J_M)^-1 J_M^T) J_K, see projectorMarginal());
 *  - drop(D): the variables D and every term touching them are removed (no marginalization).
 * Pure Eigen: no MRPT. */
#include <dynslam/framework/terms.h>
#include <dynslam/framework/variables.h>

#include <Eigen/Core>
#include <map>
#include <set>
#include <vector>

namespace dynslam::framework
{
enum class SolverKind
{
	Auto,  ///< dense up to TGaussNewtonOptions::sparse_threshold scalar unknowns, then sparse
	Dense,
	Sparse
};

struct TGaussNewtonOptions
{
	SolverKind solver = SolverKind::Auto;
	int sparse_threshold = 300;
	/** Singular J^T J: false (default) throws std::runtime_error naming the unobservable
	 * variables; true uses the pseudo-inverse (dense solver only). */
	bool allow_singular = false;
	/** Rank threshold on the pivots of the Jacobi-scaled J^T J (unit diagonal). */
	double singular_tol = 1e-12;
	/** Dense solver: also return the covariance (J^T J)^+ (O(n^3)). */
	bool compute_covariance = true;
};

struct TGaussNewtonResult
{
	double cost_before = 0;  ///< cost at x*
	double max_step = 0;     ///< max |delta| (the convergence measure)
	/** Minimum of the linearized cost, C^T C + g^T delta (g = J^T C): for an update on a
	 * prior, the NIS nu^T (H Sigma H^T + R)^-1 nu. */
	double cost_linear_min = 0;
	bool dense = true;
	Eigen::MatrixXd information;  ///< dense J^T J (dense solver only)
	Eigen::MatrixXd covariance;   ///< dense (J^T J)^+ (dense solver, compute_covariance)
};

class CRunningCost
{
public:
	// --- variables ---------------------------------------------------------------------
	/** Adds a block with its initial value (the linearization point of the next step).
	 * Throws std::invalid_argument if it exists already or the value is not finite. */
	void addVariable(const TVarKey& key, const Eigen::VectorXd& value);
	bool has(const TVarKey& key) const { return m_index.count(key) > 0; }
	/** Throws std::out_of_range naming the key if it does not exist. */
	const Eigen::VectorXd& value(const TVarKey& key) const;
	void setValue(const TVarKey& key, const Eigen::VectorXd& v);
	int dim(const TVarKey& key) const { return int(value(key).size()); }
	/** Keys in storage order (the order of the stacked state). */
	const std::vector<TVarKey>& keys() const { return m_keys; }
	size_t numVariables() const { return m_keys.size(); }
	int totalDim() const { return m_totalDim; }
	/** Offset of the block in the stacked state. */
	int offset(const TVarKey& key) const;
	Eigen::VectorXd stackedValues() const;

	// --- terms -------------------------------------------------------------------------
	/** Throws std::invalid_argument if the term references a variable that does not exist
	 * (a variable referenced before it exists) or a block of the wrong size. */
	void addTerm(const CTermPtr& term);
	const std::vector<CTermPtr>& terms() const { return m_terms; }
	/** Removes one term (by identity); returns false if it is not in the cost. */
	bool removeTerm(const CTermPtr& term);
	/** Sum of r^T W r at the current values. */
	double evaluate() const;

	// --- operations --------------------------------------------------------------------
	/** One GN step about the current values; the values become the new mean. Throws
	 * std::runtime_error on a singular system (unless allow_singular), naming variables. */
	TGaussNewtonResult gaussNewtonStep(const TGaussNewtonOptions& opts = {});
	/** Alg. 1's "cost <- ||x - mu||^2_{Sigma^-1}": all terms replaced by one prior on every
	 * variable, mean = current values, the given information (n x n, storage order). */
	void collapseToPrior(const Eigen::MatrixXd& information);
	/** Marginalizes the variables M (see the file comment); returns the new prior (null if
	 * the terms touching M touch nothing else). Throws std::runtime_error if the information
	 * on M given the rest is singular, std::out_of_range for unknown keys. */
	std::shared_ptr<CPriorTerm> marginalize(const std::vector<TVarKey>& M);
	/** Removes the variables and every term touching them. */
	void drop(const std::vector<TVarKey>& D);

	/** Joint covariance of the listed blocks under the cost linearized at the current values
	 * ((J^T J)^-1 restricted to them). Throws std::runtime_error on a singular system. */
	Eigen::MatrixXd covariance(const std::vector<TVarKey>& blocks,
	                           const TGaussNewtonOptions& opts = {}) const;

	/** Whitened stacked system of the given terms (all if empty): J (rows x totalDim, storage
	 * order) and C (rows) with cost = ||C||^2, for tests and the paper's formulas. */
	void whitenedSystem(Eigen::MatrixXd& J, Eigen::VectorXd& C,
	                    const std::vector<size_t>& termIdx = {}) const;

private:
	struct TNormal;
	void buildNormal(const std::vector<size_t>& termIdx, const std::vector<int>& localOffset,
	                 Eigen::MatrixXd& H, Eigen::VectorXd& g, double* cost) const;
	std::vector<Eigen::VectorXd> termValues(const CTerm& t) const;
	void reindex();
	[[noreturn]] void throwSingular(const Eigen::MatrixXd& Hs, const std::string& where) const;
	/** Throws the "not constrained by any term" error naming the variable holding index idx. */
	[[noreturn]] void throwUnconstrained(int idx) const;
	/** gaussNewtonStep's solve at the current values, dense or sparse normal equations: fills
	 * g (gradient, sized by the caller), the step delta and res (cost, information, covariance).*/
	void solveDense(const std::vector<size_t>& all, const TGaussNewtonOptions& opts,
	                Eigen::VectorXd& g, Eigen::VectorXd& delta, TGaussNewtonResult& res) const;
	void solveSparse(const std::vector<size_t>& all, const TGaussNewtonOptions& opts,
	                 Eigen::VectorXd& g, Eigen::VectorXd& delta, TGaussNewtonResult& res) const;
	/** marginalize()'s bookkeeping: the terms touching the variables mIdx (ascending, appended
	 * to termIdx) and the other variables those terms touch (kIdx). */
	void termsTouching(const std::set<size_t>& mIdx, std::vector<size_t>& termIdx,
	                   std::set<size_t>& kIdx) const;
	/** Removes the terms at the ascending indices termIdx and the variables varIdx; reindexes. */
	void eraseTermsAndVariables(const std::vector<size_t>& termIdx, const std::set<size_t>& varIdx);

	std::vector<TVarKey> m_keys;
	std::vector<Eigen::VectorXd> m_values;
	std::vector<int> m_offsets;
	std::map<TVarKey, size_t> m_index;
	int m_totalDim = 0;
	std::vector<CTermPtr> m_terms;
};

/** The paper's marginalization formulas (from [1]): with whitened J = [J_K J_M] and C,
 *   Omega_K = J_K^T (I - J_M (J_M^T J_M)^-1 J_M^T) J_K,
 *   d_K = -Omega_K^+ J_K^T (I - J_M (J_M^T J_M)^-1 J_M^T) C   (mean = x_K* + d_K).
 * Used by the tests to check CRunningCost::marginalize (Schur complement). */
void projectorMarginal(const Eigen::MatrixXd& J_K, const Eigen::MatrixXd& J_M,
                       const Eigen::VectorXd& C, Eigen::MatrixXd& Omega_K, Eigen::VectorXd& d_K);

/** Moore-Penrose pseudo-inverse of a symmetric PSD matrix (SelfAdjointEigenSolver;
 * eigenvalues below tol * max are treated as zero). */
Eigen::MatrixXd psdPseudoInverse(const Eigen::MatrixXd& A, double tol = 1e-12);
}  // namespace dynslam::framework
