/** libFuzzer target: bytes -> MRPT rawlog deserialization -> filter steps (fuzz_entries.h). */
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	// An exception of a type the filter does not document is a finding: abort, so libFuzzer
	// saves the input.
	if (dynslam_fuzz::rawlogBytes(data, size).unexpected_exceptions > 0) std::abort();
	return 0;
}
