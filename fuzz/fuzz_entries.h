#pragma once
/** @file fuzz_entries.h
 * The fuzzed entry points, shared by the libFuzzer targets (fuzz/, clang, DYNSLAM_FUZZ=ON) and
 * the fixed-count mutation test compiled with the normal compiler (tests/hardening). Both never
 * throw: every exception the library documents is caught; anything else (a crash, a sanitizer
 * report, an unexpected exception type) is a finding. */
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dynslam_fuzz
{
/** What one input did (for the tests' statistics). */
struct TOutcome
{
	int objects = 0;         ///< serialized objects read
	int steps = 0;           ///< filter steps run
	int rejected_steps = 0;  ///< steps the filter rejected (std::runtime_error)
	/** Steps that threw another std::exception type than documented (see fuzz_entries.cpp). */
	int unexpected_exceptions = 0;
	bool parse_error = false;  ///< the byte stream stopped with a deserialization error
	bool accepted = false;     ///< INI: options accepted
	/** The bytes crash MRPT's own deserializer (checked in a forked child, nothing else run).
	 * Known MRPT 2.5.8 issue, see doc/robustness.md; not a finding in dynslam's code. */
	bool mrpt_deserializer_crash = false;
	/** MRPT's deserializer asks for more than kChildExtraBytes (8x that under ASan) or runs
	 * for more than 20 s (a corrupt length or count field); skipped so the test cannot exhaust
	 * the machine's memory. */
	bool too_large = false;
};

constexpr int kParseOk = 0, kParseTooLarge = 3, kParseCrash = 4;
constexpr unsigned long kChildExtraBytes = 64ul << 20;  ///< 64 MB beyond what is mapped

/** Deserializes every object of the bytes with MRPT only (no filter): kParseOk when it
 * finished (cleanly or with an exception), kParseTooLarge on std::bad_alloc/length_error.
 * Run it in a child process: it may crash inside MRPT. */
int mrptParseOnly(const uint8_t* data, size_t size);
/** mrptParseOnly in a forked child (default signal handlers, address space capped unless
 * under ASan; the parent kills it when its resident set or run time gets too large):
 * kParseOk, kParseTooLarge, or kParseCrash if the child died. */
int mrptParseInChild(const uint8_t* data, size_t size);

/** Bytes = an uncompressed MRPT rawlog stream (format #1). Inputs that crash MRPT's own
 * deserializer (mrptParsesWithoutCrash, in a child process) are skipped and flagged. Objects are
 * read one at a time from a memory archive with the pairing rule of dynslam::apps::loadRawlog (an
 * action, then the next sensory frame); each pair goes through
 * CDynamicKFSLAM2D::processActionObservation (at most maxSteps, state size capped so a fuzzer
 * cannot ask for a huge covariance). */
TOutcome rawlogBytes(const uint8_t* data, size_t size, int maxSteps = 32);

/** Bytes = INI text -> CConfigFileMemory -> CDynamicKFSLAM2D::TOptions::loadFromConfigFile,
 * validate(), dumpToTextStream, then CDynamicKFSLAM2D::loadOptions and, if accepted, a few
 * filter steps on a fixed tiny input. */
TOutcome iniBytes(const uint8_t* data, size_t size);

/** Seed inputs: the first pairs of a simulated-like run serialized uncompressed, and INI files. */
std::vector<std::vector<uint8_t>> rawlogSeeds();
std::vector<std::string> iniSeeds();
}  // namespace dynslam_fuzz
