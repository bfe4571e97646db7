/** The dispatcher of dynslam/core/kernels.h: the ISA choice and the per-kernel forwarding. */
#include <dynslam/core/kernels.h>

#include <atomic>
#include <cstdlib>
#include <stdexcept>

#include "kernels/variants.h"

namespace dynslam::kernels
{
namespace
{
constexpr int kUnset = -1;
std::atomic<int> g_active{kUnset};

Isa currentIsa()
{
	int v = g_active.load(std::memory_order_relaxed);
	if (v == kUnset)
	{
		// First use: the environment, once (a bad value throws here, and again on the next call).
		v = int(isaFromEnvironmentValue(std::getenv("DYNSLAM_ISA")));
		int expected = kUnset;
		if (!g_active.compare_exchange_strong(expected, v)) v = expected;
	}
	return Isa(v);
}
}  // namespace

const char* isaName(Isa isa) { return isa == Isa::Avx2 ? "avx2" : "sse2"; }

Isa parseIsa(const std::string& name)
{
	if (name == "sse2") return Isa::Sse2;
	if (name == "avx2") return Isa::Avx2;
	throw std::runtime_error("instruction set '" + name + "' is not one of sse2, avx2");
}

bool isaCompiled(Isa isa)
{
#if defined(DYNSLAM_HAVE_AVX2_KERNELS)
	(void)isa;
	return true;
#else
	return isa == Isa::Sse2;
#endif
}

bool cpuSupports(Isa isa)
{
	if (isa == Isa::Sse2) return true;
#if defined(__x86_64__) || defined(__i386__)
	__builtin_cpu_init();
	return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
	return false;
#endif
}

bool isaAvailable(Isa isa) { return isaCompiled(isa) && cpuSupports(isa); }

Isa bestIsa() { return isaAvailable(Isa::Avx2) ? Isa::Avx2 : Isa::Sse2; }

Isa isaFromEnvironmentValue(const char* value)
{
	if (value == nullptr || *value == '\0' || std::string(value) == "auto") return bestIsa();
	Isa isa;
	try
	{
		isa = parseIsa(value);
	}
	catch (const std::runtime_error&)
	{
		throw std::runtime_error(std::string("DYNSLAM_ISA = '") + value +
		                         "': expected sse2, avx2 or auto");
	}
	if (!isaAvailable(isa))
		throw std::runtime_error(
		    std::string("DYNSLAM_ISA = ") + value + ": " +
		    (isaCompiled(isa) ? "this CPU lacks AVX2/FMA" : "not compiled into this build"));
	return isa;
}

Isa activeIsa() { return currentIsa(); }

void setActiveIsa(Isa isa)
{
	if (!isaAvailable(isa))
		throw std::runtime_error(
		    std::string("setActiveIsa(") + isaName(isa) + "): " +
		    (isaCompiled(isa) ? "this CPU lacks AVX2/FMA" : "not compiled into this build"));
	g_active.store(int(isa), std::memory_order_relaxed);
}

CScopedIsa::CScopedIsa(Isa isa) : m_previous(activeIsa()) { setActiveIsa(isa); }
CScopedIsa::~CScopedIsa() { g_active.store(int(m_previous), std::memory_order_relaxed); }

bool sparseUpdate(const TSparseUpdateArgs& a, double& nis)
{
#if defined(DYNSLAM_HAVE_AVX2_KERNELS)
	if (currentIsa() == Isa::Avx2) return avx2::sparseUpdate(a, nis);
#endif
	return sse2::sparseUpdate(a, nis);
}

void expandLevel(const TExpandLevelArgs& a)
{
#if defined(DYNSLAM_HAVE_AVX2_KERNELS)
	if (currentIsa() == Isa::Avx2) return avx2::expandLevel(a);
#endif
	sse2::expandLevel(a);
}

void productColRow(const double* A, std::ptrdiff_t r, std::ptrdiff_t k, const double* B,
                   std::ptrdiff_t c, std::ptrdiff_t ldB, double* C)
{
#if defined(DYNSLAM_HAVE_AVX2_KERNELS)
	if (currentIsa() == Isa::Avx2) return avx2::productColRow(A, r, k, B, c, ldB, C);
#endif
	sse2::productColRow(A, r, k, B, c, ldB, C);
}
}  // namespace dynslam::kernels
