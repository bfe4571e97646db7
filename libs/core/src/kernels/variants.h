#pragma once
/** The per-ISA kernel variants behind the dispatcher of dynslam/core/kernels.h: the same source
 * (kernels_body.h) compiled once per instruction set, each in its own namespace. */
#include <dynslam/core/kernels.h>

#define DYNSLAM_KERNEL_DECLARATIONS                                                          \
	bool sparseUpdate(const ::dynslam::kernels::TSparseUpdateArgs& a, double& nis);          \
	void expandLevel(const ::dynslam::kernels::TExpandLevelArgs& a);                         \
	void productColRow(const double* A, std::ptrdiff_t r, std::ptrdiff_t k, const double* B, \
	                   std::ptrdiff_t c, std::ptrdiff_t ldB, double* C);

namespace dynslam::kernels::sse2
{
DYNSLAM_KERNEL_DECLARATIONS
}
namespace dynslam::kernels::avx2
{
DYNSLAM_KERNEL_DECLARATIONS
}
