#pragma once
/** @file kernels.h
 * The hot numeric kernels of the EKF, compiled twice and chosen at run time
 * (doc/results/performance.md, section 10): once with the build's baseline flags ("sse2": x86-64's
 * SSE2 in the default, portable build) and, on x86-64, once with -mavx2 -mfma ("avx2": Eigen's
 * AVX2/FMA products). The default binary uses the AVX2 variant if the CPU it runs on has AVX2
 * and FMA, and stays runnable on any x86-64.
 *
 * Selection, in this order: setActiveIsa() (tests, benches), else the environment variable
 * DYNSLAM_ISA = sse2 | avx2 | auto, read once at the first kernel call, else auto (= avx2 where
 * available). The two variants give equal results up to rounding (FMA contractions):
 * tests/core/test_kernels_isa.cpp, tests/ekf/test_isa_highway.cpp.
 *
 * The kernels take raw storage, no Eigen types: the AVX2 variant is compiled against Eigen in a
 * renamed namespace (no template instantiation shared with the rest of the program, so no
 * AVX2 code can leak into the portable path through the linker's choice of weak symbols). */
#include <cstddef>
#include <string>

namespace dynslam::kernels
{
enum class Isa
{
	Sse2,  ///< the build's baseline flags (SSE2 on a default x86-64 build)
	Avx2   ///< -mavx2 -mfma
};

/** "sse2" or "avx2". */
const char* isaName(Isa isa);
/** "sse2" / "avx2" (not "auto"); anything else throws std::runtime_error naming the value. */
Isa parseIsa(const std::string& name);
/** The variant is compiled into this binary (avx2: only on x86 with a compiler that has the
 * flags). */
bool isaCompiled(Isa isa);
/** The CPU can run the variant (avx2: __builtin_cpu_supports("avx2") and ("fma")). */
bool cpuSupports(Isa isa);
/** isaCompiled && cpuSupports. */
bool isaAvailable(Isa isa);
/** The best available variant: avx2 if available, else sse2. */
Isa bestIsa();
/** The choice for a value of DYNSLAM_ISA: null, "" or "auto" -> bestIsa(); "sse2" / "avx2" if
 * available; an unknown value, or avx2 where it is not available, throws std::runtime_error. */
Isa isaFromEnvironmentValue(const char* value);

/** The variant the kernels use now (on the first call: isaFromEnvironmentValue of DYNSLAM_ISA). */
Isa activeIsa();
/** Use `isa` from now on, in every thread; throws std::runtime_error if it is not available. */
void setActiveIsa(Isa isa);

/** Sets the variant for its lifetime, then restores the previous one (tests, benches). */
class CScopedIsa
{
public:
	explicit CScopedIsa(Isa isa);
	~CScopedIsa();
	CScopedIsa(const CScopedIsa&) = delete;
	CScopedIsa& operator=(const CScopedIsa&) = delete;

private:
	Isa m_previous;
};

// --- Kernels --------------------------------------------------------------------------------

/** The arithmetic of ekf::sparseUpdate (see there), on raw storage; the sizes and indices are
 * checked by the caller. P is n x n row-major, row i at P + i * ldP (ldP >= n); H is m x k
 * column-major over the state entries idx[0..k); nu has m entries, R is m x m column-major. */
struct TSparseUpdateArgs
{
	double* x = nullptr;
	double* P = nullptr;
	std::ptrdiff_t n = 0, ldP = 0;
	const int* idx = nullptr;
	std::ptrdiff_t k = 0;
	const double* H = nullptr;
	std::ptrdiff_t m = 0;
	const double* nu = nullptr;
	const double* R = nullptr;
};
/** S = H P[idx,idx] H^T + R (symmetrized), W = P[:,idx] H^T L^-T (S = L L^T),
 * x += W L^-1 nu, P -= W W^T on the lower triangle, mirrored to the upper one.
 * @return false (x and P unchanged) if S is not positive definite; else true, nis = the NIS. */
bool sparseUpdate(const TSparseUpdateArgs& a, double& nis);

/** One level of the compressed EKF's global update (estimator::expandState), on raw
 * column-major storage: with the passive level's mean x (p), covariance P (p x p) and
 * cross = cov(active then, passive) (m0 x p), the entries so far' cross-covariance with the
 * compressed entries G (nf x m0), their covariance Q (m0 x m0) and mean beta (m0):
 *   xB = x + cross^T beta, CB = G cross (nf x p), BB = P + cross^T (Q cross), symmetrized.
 * The outputs are written, not read (no aliasing with the inputs). */
struct TExpandLevelArgs
{
	const double* G = nullptr;
	std::ptrdiff_t nf = 0, m0 = 0;
	const double* Q = nullptr;
	const double* beta = nullptr;
	const double* cross = nullptr;
	std::ptrdiff_t p = 0;
	const double* P = nullptr;
	const double* x = nullptr;
	double* xB = nullptr;
	double* CB = nullptr;
	double* BB = nullptr;
};
void expandLevel(const TExpandLevelArgs& a);

/** C = A B with A r x k column-major, B k x c row-major (row stride ldB >= c), C r x c
 * column-major (written, not read): the object-pose augmentation's Gamma * rows. */
void productColRow(const double* A, std::ptrdiff_t r, std::ptrdiff_t k, const double* B,
                   std::ptrdiff_t c, std::ptrdiff_t ldB, double* C);
}  // namespace dynslam::kernels
