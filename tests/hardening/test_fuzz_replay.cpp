/** Fixed-count fuzzing inside ctest: the libFuzzer entry points (fuzz/fuzz_entries.h) on the
 * seeds and on deterministic random mutations of them (bit flips, interesting bytes, inserted,
 * deleted, duplicated and truncated ranges). Any crash, sanitizer report or exception escaping
 * the entry points fails the test. Longer runs: scripts/fuzz.sh (libFuzzer, clang). */
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <random>

#include "fuzz_entries.h"

using dynslam_fuzz::TOutcome;

namespace
{
std::vector<uint8_t> mutate(std::vector<uint8_t> s, std::mt19937& g)
{
	const int n = 1 + int(g() % 8);
	for (int i = 0; i < n; ++i)
	{
		if (s.empty())
		{
			s.push_back(uint8_t(g()));
			continue;
		}
		const size_t p = g() % s.size();
		switch (g() % 7)
		{
			case 0:
				s[p] ^= uint8_t(1u << (g() % 8));
				break;
			case 1:
			{
				const uint8_t v[] = {0x00, 0xff, 0x7f, 0x80, 0x01, 0xfe};
				s[p] = v[g() % 6];
				break;
			}
			case 2:
				s[p] = uint8_t(g());
				break;
			case 3:
				s.insert(s.begin() + long(p), size_t(1 + g() % 8), uint8_t(g()));
				break;
			case 4:
				s.erase(s.begin() + long(p),
				        s.begin() + long(std::min(s.size(), p + 1 + g() % 16)));
				break;
			case 5:
			{
				const size_t q = g() % s.size(), len = std::min<size_t>(1 + g() % 32, s.size() - q);
				std::vector<uint8_t> chunk(s.begin() + long(q), s.begin() + long(q + len));
				s.insert(s.begin() + long(p), chunk.begin(), chunk.end());
				break;
			}
			case 6:
				s.resize(p);
				break;
		}
	}
	return s;
}
}  // namespace

TEST(FuzzReplay, RawlogSeedsRunCleanly)
{
	const auto seeds = dynslam_fuzz::rawlogSeeds();
	ASSERT_EQ(seeds.size(), 3u);
	const int pairs[] = {1, 3, 6};
	for (size_t i = 0; i < seeds.size(); ++i)
	{
		const TOutcome r = dynslam_fuzz::rawlogBytes(seeds[i].data(), seeds[i].size());
		EXPECT_FALSE(r.parse_error);
		EXPECT_EQ(r.objects, 2 * pairs[i]);
		EXPECT_EQ(r.steps, pairs[i]);
		EXPECT_EQ(r.rejected_steps, 0);
	}
}

TEST(FuzzReplay, RawlogMutations)
{
	const auto seeds = dynslam_fuzz::rawlogSeeds();
	std::mt19937 g(20261121);
	const int N = 80;  // each input also runs in a forked child
	int parseErrors = 0, withSteps = 0, rejected = 0, mrptCrashes = 0, tooLarge = 0;
	for (int i = 0; i < N; ++i)
	{
		const auto in = mutate(seeds[g() % seeds.size()], g);
		TOutcome r;
		ASSERT_NO_THROW(r = dynslam_fuzz::rawlogBytes(in.data(), in.size())) << "input " << i;
		if (r.mrpt_deserializer_crash && mrptCrashes++ == 0)
			std::ofstream(DYNSLAM_BINARY_DIR "/mrpt_deserializer_crash.bin", std::ios::binary)
			    .write(reinterpret_cast<const char*>(in.data()), std::streamsize(in.size()));
		parseErrors += r.parse_error;
		tooLarge += r.too_large;
		withSteps += r.steps > 0;
		rejected += r.rejected_steps;
		EXPECT_EQ(r.unexpected_exceptions, 0) << "input " << i;
	}
	std::cout << "rawlog mutations: " << N << " inputs, " << parseErrors
	          << " deserialization errors, " << withSteps << " ran filter steps, " << rejected
	          << " steps rejected, " << mrptCrashes
	          << " crash MRPT's deserializer alone (skipped; first one in " DYNSLAM_BINARY_DIR
	             "/mrpt_deserializer_crash.bin), "
	          << tooLarge << " ask MRPT for > 64 MB (skipped)\n";
	// The mutations reach both the parser's error paths and the filter.
	EXPECT_GT(parseErrors, N / 20);
	EXPECT_GT(withSteps, N / 20);
}

TEST(FuzzReplay, IniSeedsAcceptedAndMutations)
{
	const auto seeds = dynslam_fuzz::iniSeeds();
	for (const auto& s : seeds)
	{
		const TOutcome r =
		    dynslam_fuzz::iniBytes(reinterpret_cast<const uint8_t*>(s.data()), s.size());
		EXPECT_TRUE(r.accepted) << s;
		EXPECT_EQ(r.steps, 4) << s;
	}
	std::mt19937 g(7);
	const int N = 3000;
	int accepted = 0, stepped = 0;
	for (int i = 0; i < N; ++i)
	{
		const std::string& s = seeds[g() % seeds.size()];
		const auto in = mutate(std::vector<uint8_t>(s.begin(), s.end()), g);
		TOutcome r;
		ASSERT_NO_THROW(r = dynslam_fuzz::iniBytes(in.data(), in.size())) << "input " << i;
		accepted += r.accepted;
		stepped += r.steps > 0;
		EXPECT_EQ(r.unexpected_exceptions, 0) << "input " << i;
	}
	std::cout << "INI mutations: " << N << " inputs, " << accepted << " accepted, " << stepped
	          << " ran filter steps\n";
	EXPECT_GT(accepted, N / 20);
	EXPECT_LT(accepted, N - N / 20);
}

TEST(FuzzReplay, IniPreprocessorErrorsAreCaught)
{
	// Found by libFuzzer: MRPT's INI preprocessor throws from CConfigFileMemory's constructor.
	for (const std::string s :
	     {"[DynamicKFSLAM]\nSigma_v = $eval{ve\n", "[A]\nx = ${undefined_var}\n", "@define\n",
	      "[DynamicKFSLAM]\nmeasurement_model = $env{\n"})
	{
		TOutcome r;
		ASSERT_NO_THROW(
		    r = dynslam_fuzz::iniBytes(reinterpret_cast<const uint8_t*>(s.data()), s.size()))
		    << s;
		EXPECT_FALSE(r.accepted) << s;
	}
}

TEST(FuzzReplay, ExtremeNoiseFailsAsDocumented)
{
	// Found by libFuzzer: options that pass validate() but make the innovation covariance
	// numerically not positive definite. The step must fail with the documented
	// std::runtime_error (not MRPT's wrapper type), and every later step must be refused too.
	// The Cartesian seed with Sigma_v's first entry set to 1e65.
	std::string ini = dynslam_fuzz::iniSeeds().at(1);
	const std::string key = "Sigma_v = [1e-5 1e-5]";
	const size_t at = ini.find(key);
	ASSERT_NE(at, std::string::npos);
	ini.replace(at, key.size(), "Sigma_v = [1e65 1e-5]");
	const TOutcome r =
	    dynslam_fuzz::iniBytes(reinterpret_cast<const uint8_t*>(ini.data()), ini.size());
	ASSERT_TRUE(r.accepted);
	EXPECT_EQ(r.unexpected_exceptions, 0);
	EXPECT_GE(r.rejected_steps, 1);
	EXPECT_EQ(r.steps + r.rejected_steps, 4);
}

TEST(FuzzReplay, NumericKalmanMethodOutOfRangeIsRejected)
{
	// Found by libFuzzer (UBSan, "method = 5kfEKFAlaDavison"): MRPT's read_enum turns a value
	// that starts with a digit into static_cast<TKFMethod>(atoi(value)) without a range check,
	// so 5 (TKFMethod's range is 0..3) is undefined behaviour as soon as it is loaded. Every
	// such value must be rejected with an exception; under -DDYNSLAM_SANITIZE=ON an
	// out-of-range load fails this test with a UBSan report.
	const std::string seed = dynslam_fuzz::iniSeeds().at(1);  // method = kfEKFAlaDavison
	const std::string key = "method = kfEKFAlaDavison";
	const size_t at = seed.find(key);
	ASSERT_NE(at, std::string::npos);
	auto run = [&](const std::string& method)
	{
		const std::string ini =
		    seed.substr(0, at) + "method = " + method + seed.substr(at + key.size());
		TOutcome r;
		EXPECT_NO_THROW(
		    r = dynslam_fuzz::iniBytes(reinterpret_cast<const uint8_t*>(ini.data()), ini.size()))
		    << method;
		return r.accepted;
	};
	EXPECT_TRUE(run("kfEKFAlaDavison"));
	for (const std::string method : {"5kfEKFAlaDavison", "5", "2", "3", "kfIKF", "x"})
		EXPECT_FALSE(run(method)) << method;
}
