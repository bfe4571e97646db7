#!/usr/bin/env bash
# Checks that the AVX2/FMA kernel object (libs/core/src/kernels/kernels_avx2.cpp) shares no
# symbol with the rest of the program (doc/results/performance.md, section 10): every global or weak
# symbol it defines must be in its own namespaces (dynslam::kernels::avx2, the renamed Eigen
# EigenAvx2) or the exception-personality reference every C++ object has. A weak symbol outside
# them (an Eigen or standard-library inline function compiled with AVX2) could be the copy the
# linker keeps for the whole program: illegal instructions on CPUs without AVX2.
# Usage: scripts/check_kernel_symbols.sh <libdynslam_core.a>. Exit 0 clean, 1 violation,
# 77 (ctest: skipped) if the library has no AVX2 kernel object (not an x86-64 build).
set -euo pipefail
lib="${1:?usage: $0 <libdynslam_core.a>}"
NM="${NM:-nm}"
members=$("$NM" -A --defined-only "$lib" 2>/dev/null | cut -d: -f2 | sort -u)
if ! grep -q 'kernels_avx2\.cpp\.o$' <<<"$members"; then
	echo "check_kernel_symbols: no kernels_avx2.cpp.o in $lib (AVX2 variant not compiled): skipped"
	exit 77
fi
# "archive:member: address type name", global/weak definitions only (upper case, V/W, u).
avx=$("$NM" -A --defined-only "$lib" | grep 'kernels_avx2\.cpp\.o:' |
	awk '$(NF-1) ~ /^[A-Zuvw]$/ {print $(NF-1), $NF}')
own=' (_Z(ZN|GVZN|TVN|TIN|TSN|N)[rVKO]*(9EigenAvx2|7dynslam7kernels4avx2)|DW\.ref\.__gxx_personality_v0$)'
bad=$(grep -v -E "$own" <<<"$avx" || true)
# A template of another namespace instantiated with EigenAvx2 arguments (a std:: algorithm on
# Eigen types, say) is not in the list either: it is reported, to be looked at.
n=$(grep -c . <<<"$avx" || true)
if [[ -n "$bad" ]]; then
	echo "check_kernel_symbols: kernels_avx2.cpp.o defines symbols outside its own namespaces:"
	echo "$bad" | while read -r t s; do echo "  $t $(c++filt "$s")"; done
	exit 1
fi
# The portable variant and the rest of the library must not reference the renamed Eigen.
if "$NM" -A "$lib" | grep -v 'kernels_avx2\.cpp\.o:' | grep -q 'EigenAvx2'; then
	echo "check_kernel_symbols: an object other than kernels_avx2.cpp.o mentions EigenAvx2"
	exit 1
fi
echo "check_kernel_symbols: kernels_avx2.cpp.o defines $n global/weak symbols, all its own"
