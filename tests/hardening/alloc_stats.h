#pragma once
/** Bytes the process has allocated through malloc and not freed, for the memory checks of the
 * soak tests. glibc: mallinfo2 (in use in the heap plus mmapped blocks). Under AddressSanitizer,
 * whose allocator replaces glibc's (mallinfo2 then reports zeros), the sanitizer's own count. */
#include <malloc.h>

#if defined(__SANITIZE_ADDRESS__)
#define DYNSLAM_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DYNSLAM_TEST_ASAN 1
#endif
#endif
#ifdef DYNSLAM_TEST_ASAN
#include <cstddef>
// In the sanitizer runtime (libasan); GCC ships no header for it (clang: allocator_interface.h).
extern "C" size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace dynslam_test
{
inline long allocatedBytes()
{
#ifdef DYNSLAM_TEST_ASAN
	return long(__sanitizer_get_current_allocated_bytes());
#else
	const struct mallinfo2 m = mallinfo2();
	return long(m.uordblks + m.hblkhd);
#endif
}
}  // namespace dynslam_test
