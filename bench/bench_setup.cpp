/** Shared set-up of dynslam-bench (see bench_setup.h). */
#include "bench_setup.h"

#include <dynslam/sim/scenario.h>
#include <mrpt/obs/CRawlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace dynslam_bench
{
namespace
{
void fillNoise(TRun& r, const dynslam::sim::TScenarioOptions& o)
{
	r.Sigma_v = o.Sigma_v;
	r.Sigma_0 = o.Sigma_0;
	r.std_range = o.std_range;
	r.std_yaw = o.std_yaw;
}
}  // namespace

const TRun& highwayRun()
{
	static std::once_flag once;
	static TRun run;
	std::call_once(once,
	               []
	               {
		               const std::string dir = DYNSLAM_SOURCE_DIR "/datasets/";
		               fillNoise(run, dynslam::sim::loadScenario(dir + "highway_scenario.ini"));
		               mrpt::obs::CRawlog log;
		               if (!log.loadFromRawLogFile(dir + "highway.rawlog"))
			               throw std::runtime_error("cannot read " + dir + "highway.rawlog");
		               for (size_t i = 0; i + 1 < log.size(); ++i)
		               {
			               if (log.getType(i) != mrpt::obs::CRawlog::etActionCollection) continue;
			               if (log.getType(i + 1) != mrpt::obs::CRawlog::etSensoryFrame) continue;
			               run.actions.push_back(log.getAsAction(i));
			               run.frames.push_back(log.getAsObservations(i + 1));
			               ++i;
		               }
	               });
	return run;
}

const TRun& simulatedRun(const std::string& configFile, int landmarks, unsigned noiseSeed)
{
	static std::mutex mtx;
	static std::map<std::tuple<std::string, int, unsigned>, std::unique_ptr<TRun>> cache;
	std::lock_guard<std::mutex> lock(mtx);
	auto& slot = cache[{configFile, landmarks, noiseSeed}];
	if (!slot)
	{
		auto o = dynslam::sim::loadScenario(DYNSLAM_SOURCE_DIR "/config/" + configFile);
		if (landmarks >= 0)
		{
			o.highway.num_landmarks = landmarks;
			o.generated.num_landmarks = landmarks;
		}
		const auto gt = dynslam::sim::buildGroundTruth(o);
		const auto sim = dynslam::sim::simulateMeasurements(gt, o, noiseSeed);
		slot = std::make_unique<TRun>();
		slot->actions = sim.actions;
		slot->frames = sim.frames;
		fillNoise(*slot, o);
	}
	return *slot;
}

void configureDynamic(dynslam::CDynamicKFSLAM2D& f, const Eigen::Matrix2d& Sigma_v,
                      const Eigen::Matrix3d& Sigma_0, bool sparse)
{
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = dynslam::models::MeasurementModel::Cartesian;
	f.options.Sigma_v = Sigma_v;
	f.options.Sigma_0 = Sigma_0;
	f.options.motion_noise_from_action = true;
	f.options.smoothing = false;
	f.options.keep_last_poses = 1;
	f.options.sparse_static_update = sparse;
	f.KF_options.method = mrpt::bayes::kfEKFNaive;
	f.KF_options.enable_profiler = false;
	f.reset();
}

void configureAlike(mrpt::slam::CRangeBearingKFSLAM2D& rb, dynslam::CDynamicKFSLAM2D& dyn,
                    double std_range, double std_yaw, bool sparse)
{
	rb.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	rb.options.std_sensor_range = float(std_range);
	rb.options.std_sensor_yaw = float(std_yaw);
	rb.KF_options.method = mrpt::bayes::kfEKFNaive;
	rb.KF_options.enable_profiler = false;
	rb.reset();

	dyn.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	dyn.options.measurement_model = dynslam::models::MeasurementModel::RangeBearing;
	const float sr = rb.options.std_sensor_range, sy = rb.options.std_sensor_yaw;
	const float sr2 = sr * sr, sy2 = sy * sy;  // MRPT squares the float stds in float
	dyn.options.Sigma_v = Eigen::Vector2d(double(sr2), double(sy2)).asDiagonal();
	dyn.options.Sigma_0.setZero();
	dyn.options.skip_prediction_on_empty_map = true;
	dyn.options.sparse_static_update = sparse;
	dyn.KF_options.method = mrpt::bayes::kfEKFNaive;
	dyn.KF_options.enable_profiler = false;
	dyn.reset();
}

long peakRssKb()
{
	rusage ru{};
	getrusage(RUSAGE_SELF, &ru);
	return ru.ru_maxrss;
}

long currentRssKb()
{
	std::ifstream f("/proc/self/statm");
	long size = 0, resident = 0;
	if (!(f >> size >> resident)) return -1;
	return resident * (sysconf(_SC_PAGESIZE) / 1024);
}
}  // namespace dynslam_bench
