/** The kernels compiled with -mavx2 -mfma (libs/core/CMakeLists.txt), run only on CPUs that
 * have both (the dispatcher, kernels.cpp).
 *
 * Eigen is header-only: every function of it this file uses is an inline or template function,
 * emitted as a weak symbol that the linker merges with the same symbol of other translation
 * units, keeping one of them. Compiled with AVX2 here and with SSE2 elsewhere, the linker could
 * keep the AVX2 copy for the whole program (illegal instructions on older CPUs). So Eigen's
 * namespace is renamed in this file: every instantiation here is EigenAvx2::..., distinct from
 * the rest of the program's Eigen::... . The ctest KernelSymbolsIsolated (scripts/
 * check_kernel_symbols.sh) checks with nm that this object defines no other weak symbol. */
#if defined(EIGEN_CORE_H) || defined(EIGEN_WORLD_VERSION)
#error "kernels_avx2.cpp: Eigen must not be included before its namespace is renamed"
#endif
#if !defined(__AVX2__) || !defined(__FMA__)
#error "kernels_avx2.cpp must be compiled with -mavx2 -mfma"
#endif
#define Eigen EigenAvx2
#define DYNSLAM_KERNEL_NS avx2
#include "kernels_body.h"
