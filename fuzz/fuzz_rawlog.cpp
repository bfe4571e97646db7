/** libFuzzer target: bytes -> MRPT rawlog deserialization -> filter steps (fuzz_entries.h). */
#include <cstddef>
#include <cstdint>

#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	dynslam_fuzz::rawlogBytes(data, size);
	return 0;
}
