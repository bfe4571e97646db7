/** The fuzzed entry points (fuzz_entries.h). */
#include "fuzz_entries.h"

#include <dynslam/core/landmark_ids.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/serialization/CArchive.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <new>
#include <sstream>
#include <stdexcept>

namespace dynslam_fuzz
{
namespace
{
/** A few deterministic (action, frame) pairs: 6 static landmarks and one 3-feature object. */
void tinyRun(std::vector<mrpt::obs::CActionCollection::Ptr>& acts,
             std::vector<mrpt::obs::CSensoryFrame::Ptr>& sfs, int steps)
{
	for (int k = 0; k < steps; ++k)
	{
		mrpt::obs::CActionRobotMovement2D mov;
		mrpt::math::CMatrixDouble33 cov;
		cov.setZero();
		if (k > 0)
			for (int i = 0; i < 3; ++i) cov(i, i) = i < 2 ? 1e-4 : 1e-6;
		const double ux = k > 0 ? 1.0 : 0.0, uth = k > 0 ? 0.02 : 0.0;
		mov.poseChange =
		    mrpt::poses::CPosePDFGaussian::Create(mrpt::poses::CPose2D(ux, 0, uth), cov);
		mov.rawOdometryIncrementReading = mrpt::poses::CPose2D(ux, 0, uth);
		auto a = mrpt::obs::CActionCollection::Create();
		a->insert(mov);
		auto obs = mrpt::obs::CObservationBearingRange::Create();
		obs->sensorLabel = "RB";
		obs->maxSensorDistance = 50;
		obs->fieldOfView_yaw = float(2 * M_PI);
		const double ex = k * 1.0, eth = k * 0.02;
		auto add = [&](int32_t id, double fx, double fy)
		{
			const double dx = fx - ex, dy = fy;
			mrpt::obs::CObservationBearingRange::TMeasurement m;
			m.range = float(std::hypot(dx, dy));
			m.yaw = float(std::remainder(std::atan2(dy, dx) - eth, 2 * M_PI));
			m.pitch = 0;
			m.landmarkID = id;
			obs->sensedData.push_back(m);
		};
		for (int i = 0; i < 6; ++i) add(i, 3.0 * i, (i % 2 ? 5.0 : -5.0));
		for (int f = 0; f < 3; ++f)
			add(dynslam::ids::objectFeatureId(0, f), ex + 8 + 0.5 * k + std::cos(2.1 * f),
			    2 + std::sin(2.1 * f));
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		acts.push_back(a);
		sfs.push_back(sf);
	}
}

void configure(dynslam::CDynamicKFSLAM2D& f)
{
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = dynslam::models::MeasurementModel::RangeBearing;
	f.options.Sigma_v = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();
	f.reset();
}

/** Runs one step, counting documented rejections; other exception types propagate. */
void step(dynslam::CDynamicKFSLAM2D& f, const mrpt::obs::CActionCollection::Ptr& a,
          const mrpt::obs::CSensoryFrame::Ptr& sf, TOutcome& out)
{
	try
	{
		f.processActionObservation(a, sf);
		++out.steps;
	}
	catch (const std::runtime_error&)
	{
		++out.rejected_steps;
	}
	catch (const std::invalid_argument&)
	{
		++out.rejected_steps;
	}
	catch (const std::exception&)
	{
		// Not a documented type. libFuzzer once found this with accepted but extreme options
		// (Sigma_v = [1e65 1e-5]: MRPT's runOneKalmanIteration re-wrapped ekf::sparseUpdate's
		// error as mrpt::ExceptionWithCallBack); since then every failure inside a step is a
		// std::runtime_error. Counted here; the fuzz targets abort on it (a finding).
		++out.unexpected_exceptions;
	}
}
}  // namespace

int mrptParseOnly(const uint8_t* data, size_t size)
{
	mrpt::io::CMemoryStream buf;
	buf.assignMemoryNotOwn(data, size);
	auto ar = mrpt::serialization::archiveFrom(buf);
	for (;;)
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			ar >> obj;
		}
		catch (const std::bad_alloc&)
		{
			return kParseTooLarge;
		}
		catch (const std::length_error&)
		{
			return kParseTooLarge;
		}
		catch (...)
		{
			return kParseOk;
		}
	}
}

namespace
{
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif
#else
constexpr bool kAsan = false;
#endif
/** Resident bytes of a process (/proc/<pid>/statm), 0 if unreadable. */
long residentBytes(pid_t pid)
{
	long pages = 0, resident = 0;
	const std::string path = "/proc/" + std::to_string(pid) + "/statm";
	if (FILE* f = std::fopen(path.c_str(), "r"))
	{
		if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
		std::fclose(f);
	}
	return resident * sysconf(_SC_PAGESIZE);
}
}  // namespace

int mrptParseInChild(const uint8_t* data, size_t size)
{
	// Memory the child may use beyond the parent's resident set. Under ASan the heap needs
	// more (redzones, the quarantine of freed blocks), and there is no address-space cap.
	const long cap = long(kChildExtraBytes) * (kAsan ? 8 : 1);
	const long baseline = residentBytes(getpid());
	const pid_t pid = fork();
	if (pid < 0) throw std::runtime_error("fork failed");
	if (pid == 0)
	{
		for (int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) std::signal(sig, SIG_DFL);
		if (!kAsan)
		{
			// Cap the address space so a corrupt length field fails instead of allocating GBs
			// (not under ASan, which reserves terabytes of shadow memory: the parent's
			// watchdog below plays this role there). Cap: what is mapped now plus
			// kChildExtraBytes.
			unsigned long pages = 0;
			if (FILE* f = std::fopen("/proc/self/statm", "r"))
			{
				if (std::fscanf(f, "%lu", &pages) != 1) pages = 0;
				std::fclose(f);
			}
			const rlim_t as = pages * rlim_t(sysconf(_SC_PAGESIZE)) + kChildExtraBytes;
			const rlimit lim{as, as};
			setrlimit(RLIMIT_AS, &lim);
		}
		_exit(mrptParseOnly(data, size));
	}
	// Watchdog: a child whose resident set grows beyond the cap (many allocations below any
	// single-allocation limit: found by libFuzzer, 6.8 GB and growing for one corrupt rawlog)
	// or that runs longer than kChildSeconds is killed and counted as too large.
	constexpr int kChildSeconds = 20;
	const auto t0 = std::chrono::steady_clock::now();
	int status = 0;
	rusage ru{};
	for (;;)
	{
		const pid_t r = wait4(pid, &status, WNOHANG, &ru);
		if (r == pid) break;
		if (r < 0 && errno != EINTR) throw std::runtime_error("wait4 failed");
		if (residentBytes(pid) > baseline + cap ||
		    std::chrono::steady_clock::now() - t0 > std::chrono::seconds(kChildSeconds))
		{
			kill(pid, SIGKILL);
			while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
				;
			return kParseTooLarge;
		}
		usleep(200);
	}
	if (!WIFEXITED(status)) return kParseCrash;
	// Peak resident set, in case the child grew and shrank between two polls.
	if (WEXITSTATUS(status) == kParseOk && ru.ru_maxrss * 1024L > baseline + cap)
		return kParseTooLarge;
	if (WEXITSTATUS(status) == kParseOk || WEXITSTATUS(status) == kParseTooLarge)
		return WEXITSTATUS(status);
	return kParseCrash;  // e.g. a sanitizer report inside MRPT's deserializer
}

TOutcome rawlogBytes(const uint8_t* data, size_t size, int maxSteps)
{
	TOutcome out;
	const int pre = mrptParseInChild(data, size);
	if (pre != kParseOk)
	{
		out.mrpt_deserializer_crash = pre == kParseCrash;
		out.too_large = pre == kParseTooLarge;
		return out;
	}
	mrpt::io::CMemoryStream buf;
	buf.assignMemoryNotOwn(data, size);
	auto ar = mrpt::serialization::archiveFrom(buf);
	dynslam::CDynamicKFSLAM2D f;
	configure(f);
	mrpt::obs::CActionCollection::Ptr pending;
	while (out.steps + out.rejected_steps < maxSteps)
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			ar >> obj;
		}
		catch (const mrpt::serialization::CExceptionEOF&)
		{
			break;
		}
		catch (const std::bad_alloc&)
		{
			out.parse_error = true;  // a corrupt length field asking for too much memory
			break;
		}
		catch (const std::exception&)
		{
			out.parse_error = true;  // MRPT's deserialization errors (std::logic_error etc.)
			break;
		}
		++out.objects;
		if (!obj) continue;
		if (auto act = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj))
			pending = act;
		else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj); sf && pending)
		{
			// Keep the fuzzer from asking for a huge state: at most 200 measurements per step.
			const auto rb = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>();
			if (rb && rb->sensedData.size() > 200) rb->sensedData.resize(200);
			step(f, pending, sf, out);
			pending.reset();
		}
	}
	// Whatever happened, the filter state must be usable.
	if (f.fullMean().size() != f.fullCov().rows())
		throw std::logic_error("rawlogBytes: state and covariance sizes differ");
	(void)f.getEgoPose();
	(void)f.getStaticLandmarks();
	(void)f.getObjectTracks();
	return out;
}

TOutcome iniBytes(const uint8_t* data, size_t size)
{
	TOutcome out;
	const std::string text(reinterpret_cast<const char*>(data), size);
	// MRPT's INI preprocessor ($eval{}, ${}, @define) throws from the constructor on bad
	// syntax (found by the fuzzer): anything reading INI text must catch it there too.
	std::unique_ptr<mrpt::config::CConfigFileMemory> cfg;
	try
	{
		cfg = std::make_unique<mrpt::config::CConfigFileMemory>(text);
	}
	catch (const std::exception&)
	{
		return out;
	}
	const mrpt::config::CConfigFileMemory& ini = *cfg;
	dynslam::CDynamicKFSLAM2D::TOptions o;
	try
	{
		o.loadFromConfigFile(ini, "DynamicKFSLAM");
		o.validate();
		std::ostringstream dump;
		o.dumpToTextStream(dump);
	}
	catch (const std::exception&)
	{
		// Every rejection must come as an exception (a message naming the key).
	}
	dynslam::CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	try
	{
		f.loadOptions(ini);
		out.accepted = true;
	}
	catch (const std::exception&)
	{
		return out;
	}
	std::vector<mrpt::obs::CActionCollection::Ptr> acts;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> sfs;
	tinyRun(acts, sfs, 4);
	for (size_t k = 0; k < acts.size(); ++k) step(f, acts[k], sfs[k], out);
	return out;
}

std::vector<std::vector<uint8_t>> rawlogSeeds()
{
	std::vector<mrpt::obs::CActionCollection::Ptr> acts;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> sfs;
	tinyRun(acts, sfs, 6);
	std::vector<std::vector<uint8_t>> seeds;
	for (size_t n : {size_t(1), size_t(3), size_t(6)})
	{
		mrpt::io::CMemoryStream buf;
		auto ar = mrpt::serialization::archiveFrom(buf);
		for (size_t k = 0; k < n; ++k) ar << *acts[k] << *sfs[k];
		const auto* p = static_cast<const uint8_t*>(buf.getRawBufferData());
		seeds.emplace_back(p, p + buf.getTotalBytesCount());
	}
	return seeds;
}

std::vector<std::string> iniSeeds()
{
	const std::string good = R"([DynamicKFSLAM]
measurement_model = range_bearing
Sigma_v = [1e-4 1e-6]
motion_noise = action
Sigma_0 = [1e-6 1e-6 1e-8]
Sigma_xi = [0.1 0.1]
smoothing = true
Sigma_s = [0.01 0.01 0.01]
keep_last_poses = 3
drop_static_after_unseen_steps = 5
static_update = sparse
[DynamicKFSLAM_KalmanFilter]
method = kfEKFNaive
)";
	const std::string cart = R"([DynamicKFSLAM]
measurement_model = cartesian
Sigma_v = [1e-5 1e-5]
motion_noise = config
Sigma_w = [1e-5 1e-5 1e-7]
Sigma_0 = [1e-6 1e-6 1e-8]
Sigma_xi = [0.1 0.1]
smoothing = false
keep_last_poses = 1
[DynamicKFSLAM_KalmanFilter]
method = kfEKFAlaDavison
)";
	return {good, cart};
}
}  // namespace dynslam_fuzz
