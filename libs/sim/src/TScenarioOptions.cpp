/** @file TScenarioOptions.cpp
 * Strict reading of a scenario INI into TScenarioOptions. */
#include <dynslam/common/config_utils.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "options_format.h"
#include "options_sections.h"

namespace dynslam::sim
{
namespace cfg = dynslam::config;
using detail::fmt;
using detail::fmtMatrix;
using detail::fmtRamps;
using mrpt::config::CConfigFileBase;

namespace detail
{
long readCount(const CConfigFileBase& c, const std::string& sec, const std::string& key, long def,
               bool required, long maxValue)
{
	const long n = cfg::readInt(c, sec, key, def, required);
	if (n < 0) cfg::fail(sec, key, std::to_string(n), "negative count");
	if (n > maxValue)
		cfg::fail(sec, key, std::to_string(n), "larger than " + std::to_string(maxValue));
	return n;
}
}  // namespace detail
using detail::readCount;
using detail::readGenerated;

namespace
{
std::string lower(std::string s)
{
	std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
	return s;
}

/** The numbers of a list such as `[a b; c d]` (brackets, commas, semicolons ignored); empty if
 * the key is missing. */
std::vector<double> readNumberList(const CConfigFileBase& c, const std::string& sec,
                                   const std::string& key)
{
	const std::string v = cfg::readString(c, sec, key, "");
	std::string s = v;
	for (char& ch : s)
		if (ch == '[' || ch == ']' || ch == ',' || ch == ';') ch = ' ';
	std::istringstream is(s);
	std::vector<double> nums;
	std::string tok;
	while (is >> tok)
	{
		char* e = nullptr;
		const double d = std::strtod(tok.c_str(), &e);
		if (e == tok.c_str() || *e != '\0' || !std::isfinite(d))
			cfg::fail(sec, key, v, "'" + tok + "' is not a finite number");
		nums.push_back(d);
	}
	return nums;
}

/** landmark_gaps: pairs [start end; ...] with start < end. */
std::vector<std::pair<double, double>> readGaps(const CConfigFileBase& c, const std::string& sec,
                                                const std::string& key)
{
	const std::vector<double> nums = readNumberList(c, sec, key);
	const std::string v = cfg::readString(c, sec, key, "");
	if (nums.size() % 2 != 0)
		cfg::fail(sec, key, v,
		          "expected pairs (start end), got " + std::to_string(nums.size()) + " numbers");
	std::vector<std::pair<double, double>> gaps;
	for (size_t i = 0; i < nums.size(); i += 2)
	{
		if (!(nums[i] < nums[i + 1])) cfg::fail(sec, key, v, "a gap needs start < end");
		gaps.emplace_back(nums[i], nums[i + 1]);
	}
	return gaps;
}

std::vector<TRamp> readRamps(const CConfigFileBase& c, const std::string& sec,
                             const std::string& key)
{
	const std::string v = cfg::readString(c, sec, key, "");
	const std::vector<double> nums = readNumberList(c, sec, key);
	if (nums.size() % 3 != 0)
		cfg::fail(sec, key, v,
		          "expected triples (t_start duration target), got " + std::to_string(nums.size()) +
		              " numbers");
	std::vector<TRamp> r;
	for (size_t i = 0; i < nums.size(); i += 3) r.push_back({nums[i], nums[i + 1], nums[i + 2]});
	try
	{
		CSmoothProfile check(0, r);
	}
	catch (const std::invalid_argument& e)
	{
		cfg::fail(sec, key, v, e.what());
	}
	return r;
}

uint32_t readSeed(const CConfigFileBase& c, const std::string& sec, const std::string& key)
{
	const long s = cfg::readInt(c, sec, key, 0, true);
	if (s < 0 || s > long(UINT32_MAX))
		cfg::fail(sec, key, std::to_string(s), "seed must be in [0, 4294967295]");
	return uint32_t(s);
}

int readLane(const CConfigFileBase& c, const std::string& sec, const std::string& key, int numLanes)
{
	const long l = cfg::readInt(c, sec, key, 0, true);
	if (l < 0 || l >= numLanes)
		cfg::fail(sec, key, std::to_string(l),
		          "lane outside the road (lanes 0.." + std::to_string(numLanes - 1) + ")");
	return int(l);
}

void checkLanes(const std::vector<TRamp>& r, const std::string& sec, const std::string& key,
                int numLanes)
{
	for (const TRamp& x : r)
		if (x.target != std::floor(x.target) || x.target < 0 || x.target > numLanes - 1)
			cfg::fail(sec, key, fmtRamps(r),
			          "lane change to lane " + fmt(x.target) + " outside the road (lanes 0.." +
			              std::to_string(numLanes - 1) + ")");
}

/** A derived key written by dumpToTextStream may be present: it must agree. */
void checkDerived(const CConfigFileBase& c, const std::string& sec, const std::string& key,
                  const Eigen::MatrixXd& expected)
{
	if (!cfg::has(c, sec, key)) return;
	const std::string v = cfg::readString(c, sec, key, "");
	std::string s = v;
	for (char& ch : s)
		if (ch == '[' || ch == ']' || ch == ',' || ch == ';') ch = ' ';
	std::istringstream is(s);
	std::vector<double> nums;
	double d;
	while (is >> d) nums.push_back(d);
	const bool diag = expected.rows() > 1 && Eigen::Index(nums.size()) == expected.rows();
	bool ok = Eigen::Index(nums.size()) == expected.size() || diag;
	for (Eigen::Index i = 0; ok && i < expected.rows(); ++i)
		for (Eigen::Index j = 0; ok && j < expected.cols(); ++j)
		{
			const double got = diag ? (i == j ? nums[i] : 0.0) : nums[i * expected.cols() + j];
			ok = std::abs(got - expected(i, j)) <=
			         1e-9 * std::max(1e-300, std::abs(expected(i, j))) ||
			     got == expected(i, j);
		}
	if (!ok)
		cfg::fail(sec, key, v,
		          "conflicts with the value derived from the noise level (" + fmtMatrix(expected) +
		              "); use level = custom to set it");
}

/** Issue 12: start_moving_at_s, stop_at_s, start_stop_duration_s of an agent. No speed or
 * lateral change while parked or stopped, nor during the start and stop ramps. */
void readStartStop(const CConfigFileBase& c, const std::string& sec, THighwayAgent& a)
{
	const bool hasStart = cfg::has(c, sec, "start_moving_at_s"),
	           hasStop = cfg::has(c, sec, "stop_at_s");
	a.start_stop_duration_s = cfg::readPositive(c, sec, "start_stop_duration_s", 4);
	const double d = a.start_stop_duration_s;
	const std::vector<TRamp>& lat =
	    a.kind == THighwayAgent::Kind::Car ? a.lane_changes : a.lateral_moves;
	const char* latKey = a.kind == THighwayAgent::Kind::Car ? "lane_changes" : "lateral_moves";
	if (hasStart)
	{
		a.start_moving_at_s = cfg::readNonNegative(c, sec, "start_moving_at_s", 0, true);
		const double t0 = a.start_moving_at_s;
		if (!(a.speed > 0))
			cfg::fail(sec, "speed", fmt(a.speed), "must be > 0: the speed after start_moving_at_s");
		if (!a.speed_changes.empty() && a.speed_changes.front().t_start < t0 + d)
			cfg::fail(
			    sec, "speed_changes", fmtRamps(a.speed_changes),
			    "starts before the start ramp ends (start_moving_at_s + start_stop_duration_s = " +
			        fmt(t0 + d) + ")");
		if (!lat.empty() && lat.front().t_start < t0)
			cfg::fail(sec, latKey, fmtRamps(lat), "moves sideways while parked");
	}
	if (hasStop)
	{
		a.stop_at_s = cfg::readPositive(c, sec, "stop_at_s", 1, true);
		const double t1 = a.stop_at_s - d;
		for (const std::vector<TRamp>* r : {&std::as_const(a.speed_changes), &lat})
			if (!r->empty() && r->back().t_start + r->back().duration > t1)
				cfg::fail(sec, "stop_at_s", fmt(a.stop_at_s),
				          "a speed or lateral change ends after the stop ramp starts (" + fmt(t1) +
				              " s)");
		if (t1 < (hasStart ? a.start_moving_at_s + d : 0.0))
			cfg::fail(sec, "stop_at_s", fmt(a.stop_at_s),
			          "the stop ramp starts before t = 0 or before the start ramp ends");
	}
}

THighwayAgent readAgent(const CConfigFileBase& c, const std::string& sec, const THighwayOptions& h,
                        bool isEgo)
{
	THighwayAgent a;
	a.section = sec;
	if (isEgo)
	{
		cfg::rejectUnknownKeys(c, sec,
		                       {"speed", "speed_changes", "lane_changes", "length", "width"});
		a.kind = THighwayAgent::Kind::Car;
		a.x0 = 0;
		a.lane0 = h.ego_lane;
	}
	else
	{
		cfg::rejectUnknownKeys(c, sec,
		                       {"type", "x0", "lane0", "y0", "speed", "speed_changes",
		                        "lane_changes", "lateral_moves", "length", "width", "num_features",
		                        "start_moving_at_s", "stop_at_s", "start_stop_duration_s"});
		a.kind = cfg::readChoice(c, sec, "type", {"car", "pedestrian"}, 0, true) == 0
		             ? THighwayAgent::Kind::Car
		             : THighwayAgent::Kind::Pedestrian;
		a.x0 = cfg::readDouble(c, sec, "x0", 0, true);
	}
	a.speed = cfg::readDouble(c, sec, "speed", 0, true);
	a.speed_changes = readRamps(c, sec, "speed_changes");
	const bool car = a.kind == THighwayAgent::Kind::Car;
	if (car)
	{
		if (!isEgo) a.lane0 = readLane(c, sec, "lane0", h.num_lanes);
		a.lane_changes = readRamps(c, sec, "lane_changes");
		checkLanes(a.lane_changes, sec, "lane_changes", h.num_lanes);
		for (const char* k : {"y0", "lateral_moves"})
			if (cfg::has(c, sec, k))
				cfg::fail(sec, k, cfg::readString(c, sec, k, ""), "only for type = pedestrian");
		a.length = cfg::readPositive(c, sec, "length", 4.5);
		a.width = cfg::readPositive(c, sec, "width", 1.8);
		if (a.width > h.lane_width) cfg::fail(sec, "width", fmt(a.width), "wider than a lane");
		a.num_features = int(cfg::readInt(c, sec, "num_features", 4));
		if (a.num_features != 4)
			cfg::fail(sec, "num_features", std::to_string(a.num_features),
			          "a car has 4 corner features");
		if (a.speed < 0) cfg::fail(sec, "speed", fmt(a.speed), "a car cannot drive backwards");
		for (const TRamp& r : a.speed_changes)
			if (r.target < 0)
				cfg::fail(sec, "speed_changes", fmtRamps(a.speed_changes), "negative speed");
	}
	else
	{
		a.y0 = cfg::readDouble(c, sec, "y0", 0, true);
		a.lateral_moves = readRamps(c, sec, "lateral_moves");
		for (const char* k : {"lane0", "lane_changes"})
			if (cfg::has(c, sec, k))
				cfg::fail(sec, k, cfg::readString(c, sec, k, ""), "only for type = car");
		a.width = cfg::readPositive(c, sec, "width", 0.5);
		a.length = 0;
		a.num_features = int(cfg::readInt(c, sec, "num_features", 2));
		if (a.num_features != 1 && a.num_features != 2)
			cfg::fail(sec, "num_features", std::to_string(a.num_features),
			          "a pedestrian has 1 or 2 features");
	}
	if (isEgo && !(a.speed > 0)) cfg::fail(sec, "speed", fmt(a.speed), "the ego must move (> 0)");
	if (!isEgo) readStartStop(c, sec, a);
	const bool changes =
	    !a.speed_changes.empty() || !a.lane_changes.empty() || !a.lateral_moves.empty();
	if (!isEgo && a.speed == 0 && changes && std::isnan(a.start_moving_at_s))
		cfg::fail(sec, "speed", "0",
		          "a parked agent with later changes needs start_moving_at_s (its true class)");
	return a;
}

/** Reads [Highway], [Ego] and [Agent<i>] into h (defaults kept for absent optional keys). */
void readHighway(const CConfigFileBase& c, THighwayOptions& h)
{
	const std::string H = "Highway";
	cfg::rejectUnknownKeys(c, H,
	                       {"length", "num_lanes", "lane_width", "ego_lane", "num_landmarks",
	                        "landmark_offset_min", "landmark_offset_max", "num_agents"});
	h.length = cfg::readPositive(c, H, "length", 1000, true);
	h.num_lanes = int(readCount(c, H, "num_lanes", 3, true, 100));
	if (h.num_lanes < 1) cfg::fail(H, "num_lanes", "0", "need at least one lane");
	h.lane_width = cfg::readPositive(c, H, "lane_width", 3.5, true);
	h.ego_lane = readLane(c, H, "ego_lane", h.num_lanes);
	h.num_landmarks = int(readCount(c, H, "num_landmarks", 40, true, ids::kStaticMax + 1));
	h.landmark_offset_min = cfg::readNonNegative(c, H, "landmark_offset_min", 3, true);
	h.landmark_offset_max = cfg::readPositive(c, H, "landmark_offset_max", 30, true);
	if (h.landmark_offset_max < h.landmark_offset_min)
		cfg::fail(H, "landmark_offset_max", fmt(h.landmark_offset_max),
		          "smaller than landmark_offset_min");
	const long na = readCount(c, H, "num_agents", 3, true, 1000);
	h.ego = readAgent(c, "Ego", h, true);
	h.ego.section = "Ego";
	for (long i = 1; i <= na; ++i)
		h.agents.push_back(readAgent(c, "Agent" + std::to_string(i), h, false));
}

/** Reads [Effects] (issue 12); all off when the section is absent. */
void readEffects(const CConfigFileBase& c, TReadingEffects& e)
{
	const std::string E = "Effects";
	cfg::rejectUnknownKeys(c, E,
	                       {"anonymous_ids", "missed_detection_probability", "clutter_per_step",
	                        "clutter_ids", "track_break_gap", "track_break_probability",
	                        "unknown_id_probability", "detection_groups"});
	e.anonymous_ids = cfg::readBool(c, E, "anonymous_ids", false);
	e.detection_groups = cfg::readBool(c, E, "detection_groups", false);
	e.missed_detection_probability = cfg::readNonNegative(c, E, "missed_detection_probability", 0);
	if (e.missed_detection_probability >= 1)
		cfg::fail(E, "missed_detection_probability", fmt(e.missed_detection_probability),
		          "must be in [0, 1)");
	e.clutter_per_step = int(readCount(c, E, "clutter_per_step", 0, false, 100000));
	e.clutter_unknown_ids = cfg::readChoice(c, E, "clutter_ids", {"fresh", "unknown"}, 0) == 1;
	e.track_break_gap = int(readCount(c, E, "track_break_gap", 0, false, 100'000'000));
	e.track_break_probability = cfg::readNonNegative(c, E, "track_break_probability", 0);
	if (e.track_break_probability > 1)
		cfg::fail(E, "track_break_probability", fmt(e.track_break_probability),
		          "must be in [0, 1]");
	e.unknown_id_probability = cfg::readNonNegative(c, E, "unknown_id_probability", 0);
	if (e.unknown_id_probability > 1)
		cfg::fail(E, "unknown_id_probability", fmt(e.unknown_id_probability), "must be in [0, 1]");
}

/** [Noise] start_from_prior, object_accel_psd (the model-matched truth, truth_noise.h). */
void readModelMatchedTruth(const CConfigFileBase& c, const std::string& N, TScenarioOptions& o)
{
	o.start_from_prior = cfg::readBool(c, N, "start_from_prior", false);
	o.object_accel_psd = cfg::readVector(c, N, "object_accel_psd", Eigen::Vector3d::Zero(), 3);
	if (!o.object_accel_psd.allFinite() || (o.object_accel_psd.array() < 0).any())
		cfg::fail(N, "object_accel_psd", fmtMatrix(o.object_accel_psd.transpose()),
		          "must be finite and >= 0");
}
}  // namespace

bool TScenarioOptions::objectMovingAt(size_t obj, double t) const
{
	if (type != ScenarioType::Highway) return true;
	if (obj >= highway.agents.size())
		throw std::out_of_range("objectMovingAt: no object " + std::to_string(obj));
	const THighwayAgent& a = highway.agents[obj];
	if (a.speed == 0 && std::isnan(a.start_moving_at_s)) return false;  // parked for good
	if (!std::isnan(a.start_moving_at_s) && !(t > a.start_moving_at_s)) return false;
	if (!std::isnan(a.stop_at_s) && t >= a.stop_at_s) return false;
	return true;
}

void TScenarioOptions::loadFromConfigFile(const CConfigFileBase& c, const std::string&)
{
	*this = TScenarioOptions();
	const std::string S = "Scenario", SE = "Sensor", N = "Noise";
	cfg::rejectUnknownKeys(
	    c, S,
	    {"type", "name", "dt", "steps", "world_seed", "noise_seed", "start_time", "landmark_gaps"});
	type = cfg::readChoice(c, S, "type", {"highway", "generated"}, 0, true) == 0
	           ? ScenarioType::Highway
	           : ScenarioType::Generated;
	name = cfg::readString(c, S, "name", type == ScenarioType::Highway ? "highway" : "generated");
	if (name.empty() || name.find_first_of("/\\ ") != std::string::npos)
		cfg::fail(S, "name", name, "must be a non-empty file base name without spaces or slashes");
	dt = cfg::readPositive(c, S, "dt", 0.5, true);
	steps = int(readCount(c, S, "steps", 120, true, 100'000'000));
	if (steps < 1) cfg::fail(S, "steps", std::to_string(steps), "need at least 1 step");
	world_seed = readSeed(c, S, "world_seed");
	noise_seed = readSeed(c, S, "noise_seed");
	start_time = cfg::readNonNegative(c, S, "start_time", 1.6e9);
	landmark_gaps = readGaps(c, S, "landmark_gaps");

	cfg::rejectUnknownKeys(c, SE,
	                       {"range", "label", "noise_model", "typical_range", "sensor_pose"});
	sensor_range = cfg::readPositive(c, SE, "range", 55, true);
	sensor_label = cfg::readString(c, SE, "label", "RB");
	noise_model = cfg::readChoice(c, SE, "noise_model", {"cartesian", "range_bearing"}, 0) == 0
	                  ? models::MeasurementModel::Cartesian
	                  : models::MeasurementModel::RangeBearing;
	typical_range = cfg::readPositive(c, SE, "typical_range", sensor_range / 2);
	sensor_pose = cfg::readVector(c, SE, "sensor_pose", Eigen::Vector3d::Zero(), 3);

	cfg::rejectUnknownKeys(c, N,
	                       {"level", "sigma_w", "sigma_v", "sigma_0", "std_range", "std_yaw",
	                        "std_yaw_deg", "odometry_rate_bias_deg_s", "odometry_scale_error",
	                        "start_from_prior", "object_accel_psd"});
	odometry_rate_bias = cfg::readDouble(c, N, "odometry_rate_bias_deg_s", 0) * M_PI / 180;
	odometry_scale_error = cfg::readDouble(c, N, "odometry_scale_error", 0);
	readModelMatchedTruth(c, N, *this);
	const std::string lvl = cfg::requireString(c, N, "level");
	if (lower(lvl) == "custom")
	{
		noise_level = "custom";
		Sigma_w = cfg::readCovariance(c, N, "sigma_w", Eigen::Matrix3d::Zero(), 3, true, true);
		Sigma_v = cfg::readCovariance(c, N, "sigma_v", Eigen::Matrix2d::Zero(), 2, true, true);
		Sigma_0 = cfg::readCovariance(c, N, "sigma_0", Sigma_w, 3, false, true);
		updateEquivalentStds();
	}
	else
	{
		try
		{
			setNoiseLevel(lvl);
		}
		catch (const std::invalid_argument& e)
		{
			cfg::fail(N, "level", lvl, e.what());
		}
		checkDerived(c, N, "sigma_w", Sigma_w);
		checkDerived(c, N, "sigma_v", Sigma_v);
		checkDerived(c, N, "sigma_0", Sigma_0);
	}
	if (noise_model == models::MeasurementModel::RangeBearing)
	{
		std_range = cfg::readNonNegative(c, N, "std_range", 0, true);
		std_yaw = cfg::readNonNegative(c, N, "std_yaw", 0, true);
	}
	else
	{
		checkDerived(c, N, "std_range", Eigen::Matrix<double, 1, 1>(std_range));
		checkDerived(c, N, "std_yaw", Eigen::Matrix<double, 1, 1>(std_yaw));
	}
	checkDerived(c, N, "std_yaw_deg", Eigen::Matrix<double, 1, 1>(std_yaw * 180 / M_PI));

	if (type == ScenarioType::Highway)
		readHighway(c, highway);
	else
		readGenerated(c, generated);
	readEffects(c, effects);
	detail::readObjectMotion(c, *this);
	validate();
}

void TScenarioOptions::validate() const
{
	if (!(dt > 0)) throw std::invalid_argument("[Scenario] dt must be > 0");
	if (steps < 1) throw std::invalid_argument("[Scenario] steps must be >= 1");
	if (!(sensor_range > 0)) throw std::invalid_argument("[Sensor] range must be > 0");
	if (!sensor_pose.allFinite())
		throw std::invalid_argument("[Sensor] sensor_pose must be finite");
	if (!Sigma_w.allFinite() || !Sigma_v.allFinite() || !Sigma_0.allFinite())
		throw std::invalid_argument("[Noise] covariances must be finite");
	if (!std::isfinite(odometry_rate_bias) || !(std::abs(odometry_scale_error) < 1))
		throw std::invalid_argument(
		    "[Noise] odometry_rate_bias_deg_s must be finite and odometry_scale_error in (-1, 1)");
	if (!object_accel_psd.allFinite() || (object_accel_psd.array() < 0).any())
		throw std::invalid_argument("[Noise] object_accel_psd must be finite and >= 0");
	const TObjectMotionOptions& m = object_motion;
	if (m.markov && (!(m.switch_prob >= 0 && m.switch_prob < 1) || !m.accel_psd.allFinite() ||
	                 !m.manoeuvre_psd.allFinite() || (m.accel_psd.array() < 0).any() ||
	                 (m.manoeuvre_psd.array() < 0).any() || m.initial_mode < 0 ||
	                 m.initial_mode > 3 || !object_accel_psd.isZero()))
		throw std::invalid_argument(
		    "[ObjectMotion] markov: switch_prob in [0, 1), PSDs finite and >= 0, initial_mode "
		    "0..3, and no [Noise] object_accel_psd");
}

TScenarioOptions loadScenario(const std::string& iniPath)
{
	if (!std::filesystem::exists(iniPath))
		throw std::runtime_error("scenario INI file not found: " + iniPath);
	mrpt::config::CConfigFile f(iniPath);
	TScenarioOptions o;
	try
	{
		o.loadFromConfigFile(f);
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument("scenario file '" + iniPath + "': " + e.what());
	}
	return o;
}

TScenarioOptions loadScenarioFromText(const std::string& iniText)
{
	mrpt::config::CConfigFileMemory f(iniText);
	TScenarioOptions o;
	o.loadFromConfigFile(f);
	return o;
}
}  // namespace dynslam::sim
