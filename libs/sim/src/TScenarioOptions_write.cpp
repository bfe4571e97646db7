/** @file TScenarioOptions_write.cpp
 * The noise grid and the effective-configuration writer of TScenarioOptions. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/io/number_format.h>
#include <dynslam/sim/TScenarioOptions.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <stdexcept>

#include "options_format.h"
#include "options_sections.h"

namespace dynslam::sim
{
namespace detail
{
std::string fmt(double v) { return io::formatShortest(v); }

std::string fmtMatrix(const Eigen::MatrixXd& m)
{
	std::string s = "[";
	for (Eigen::Index i = 0; i < m.rows(); ++i)
	{
		for (Eigen::Index j = 0; j < m.cols(); ++j) s += (j ? " " : "") + fmt(m(i, j));
		if (i + 1 < m.rows()) s += "; ";
	}
	return s + "]";
}

std::string fmtRamps(const std::vector<TRamp>& r)
{
	std::string s = "[";
	for (size_t i = 0; i < r.size(); ++i)
		s +=
		    (i ? "; " : "") + fmt(r[i].t_start) + " " + fmt(r[i].duration) + " " + fmt(r[i].target);
	return s + "]";
}

/** A list of (t_start, duration, target) triples, e.g. `[10 4 2; 30 4 1]`; empty if missing. */
}  // namespace detail

using detail::fmt;
using detail::fmtMatrix;
using detail::fmtRamps;

namespace
{
std::string lowered(std::string s)
{
	std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
	return s;
}

void dumpAgent(std::ostream& o, const THighwayAgent& a, bool isEgo)
{
	o << "\n[" << a.section << "]\n";
	const bool car = a.kind == THighwayAgent::Kind::Car;
	if (!isEgo)
	{
		o << "type = " << (car ? "car" : "pedestrian") << "\n";
		o << "x0 = " << fmt(a.x0) << "\n";
		if (car)
			o << "lane0 = " << a.lane0 << "\n";
		else
			o << "y0 = " << fmt(a.y0) << "\n";
	}
	o << "speed = " << fmt(a.speed) << "\n";
	o << "speed_changes = " << fmtRamps(a.speed_changes) << "\n";
	if (car)
		o << "lane_changes = " << fmtRamps(a.lane_changes) << "\n";
	else
		o << "lateral_moves = " << fmtRamps(a.lateral_moves) << "\n";
	if (car) o << "length = " << fmt(a.length) << "\n";
	o << "width = " << fmt(a.width) << "\n";
	if (!isEgo) o << "num_features = " << a.num_features << "\n";
	if (!std::isnan(a.start_moving_at_s))
		o << "start_moving_at_s = " << fmt(a.start_moving_at_s) << "\n";
	if (!std::isnan(a.stop_at_s)) o << "stop_at_s = " << fmt(a.stop_at_s) << "\n";
	if (!std::isnan(a.start_moving_at_s) || !std::isnan(a.stop_at_s))
		o << "start_stop_duration_s = " << fmt(a.start_stop_duration_s) << "\n";
}

/** [Effects] only when set, so that the effective configuration of a scenario without them
 * is unchanged. */
void dumpEffects(std::ostream& o, const TReadingEffects& e)
{
	if (!e.any() && !e.clutter_unknown_ids && !e.detection_groups) return;
	o << "\n[Effects]\n";
	o << "anonymous_ids = " << (e.anonymous_ids ? "true" : "false") << "\n";
	o << "missed_detection_probability = " << fmt(e.missed_detection_probability) << "\n";
	o << "clutter_per_step = " << e.clutter_per_step << "\n";
	o << "clutter_ids = " << (e.clutter_unknown_ids ? "unknown" : "fresh") << "\n";
	o << "track_break_gap = " << e.track_break_gap << "\n";
	o << "track_break_probability = " << fmt(e.track_break_probability) << "\n";
	if (e.unknown_id_probability > 0)
		o << "unknown_id_probability = " << fmt(e.unknown_id_probability) << "\n";
	if (e.detection_groups) o << "detection_groups = true\n";
}
}  // namespace

TNoiseLevel noiseLevel(const std::string& name)
{
	const std::string l = lowered(name);
	TNoiseLevel n;
	if (l == "none") return n;
	if (l.size() == 4 && l[0] == 'w' && l[2] == 'v' && l[1] >= '1' && l[1] <= '3' && l[3] >= '1' &&
	    l[3] <= '3')
	{
		// The literals of eq. (5)-(7).
		static const double xy[] = {1e-6, 1e-5, 1e-4}, th[] = {1e-8, 1e-7, 1e-6};
		const int w = l[1] - '1', v = l[3] - '1';
		n.Sigma_w.diagonal() << xy[w], xy[w], th[w];
		n.Sigma_v = xy[v] * Eigen::Matrix2d::Identity();
		return n;
	}
	throw std::invalid_argument("unknown noise level '" + name +
	                            "' (expected w1v1..w3v3, none or custom)");
}

void TScenarioOptions::setNoiseLevel(const std::string& level)
{
	const TNoiseLevel n = noiseLevel(level);
	noise_level = lowered(level);
	Sigma_w = n.Sigma_w;
	Sigma_v = n.Sigma_v;
	Sigma_0 = Sigma_w;
	updateEquivalentStds();
}

void TScenarioOptions::updateEquivalentStds()
{
	if (noise_model != models::MeasurementModel::Cartesian) return;
	// Cartesian noise of std s on z gives, to first order, range std s and yaw std s / r.
	const double s = std::sqrt(0.5 * Sigma_v.trace());
	std_range = s;
	std_yaw = s / typical_range;
}

void TScenarioOptions::dumpToTextStream(std::ostream& o) const
{
	o << "# Effective scenario configuration written by dynslam-simulate (loadable as is).\n";
	o << "[Scenario]\n";
	o << "type = " << (type == ScenarioType::Highway ? "highway" : "generated") << "\n";
	o << "name = " << name << "\n";
	o << "dt = " << fmt(dt) << "\n";
	o << "steps = " << steps << "\n";
	o << "world_seed = " << world_seed << "\n";
	o << "noise_seed = " << noise_seed << "\n";
	o << "start_time = " << fmt(start_time) << "\n";
	if (!landmark_gaps.empty())
	{
		o << "landmark_gaps = [";
		for (size_t i = 0; i < landmark_gaps.size(); ++i)
			o << (i ? "; " : "") << fmt(landmark_gaps[i].first) << " "
			  << fmt(landmark_gaps[i].second);
		o << "]\n";
	}
	o << "\n[Sensor]\n";
	o << "range = " << fmt(sensor_range) << "\n";
	o << "label = " << sensor_label << "\n";
	o << "noise_model = " << models::toString(noise_model) << "\n";
	o << "typical_range = " << fmt(typical_range) << "\n";
	// Only when set: the shipped datasets (whose rawlog holds this text as a comment) stay
	// byte-identical to a fresh regeneration.
	if (!sensor_pose.isZero())
		o << "sensor_pose = " << fmt(sensor_pose[0]) << " " << fmt(sensor_pose[1]) << " "
		  << fmt(sensor_pose[2]) << "\n";
	o << "\n[Noise]\n";
	o << "level = " << noise_level << "\n";
	o << "sigma_w = " << fmtMatrix(Sigma_w) << "\n";
	o << "sigma_v = " << fmtMatrix(Sigma_v) << "\n";
	o << "sigma_0 = " << fmtMatrix(Sigma_0) << "\n";
	o << "std_range = " << fmt(std_range) << "\n";
	o << "std_yaw = " << fmt(std_yaw) << "\n";
	o << "std_yaw_deg = " << fmt(std_yaw * 180 / M_PI) << "\n";
	if (odometry_rate_bias != 0)
		o << "odometry_rate_bias_deg_s = " << fmt(odometry_rate_bias * 180 / M_PI) << "\n";
	if (odometry_scale_error != 0)
		o << "odometry_scale_error = " << fmt(odometry_scale_error) << "\n";
	if (start_from_prior) o << "start_from_prior = true\n";
	if (!object_accel_psd.isZero())
		o << "object_accel_psd = [" << fmt(object_accel_psd[0]) << " " << fmt(object_accel_psd[1])
		  << " " << fmt(object_accel_psd[2]) << "]\n";
	if (type == ScenarioType::Highway)
	{
		const THighwayOptions& h = highway;
		o << "\n[Highway]\n";
		o << "length = " << fmt(h.length) << "\n";
		o << "num_lanes = " << h.num_lanes << "\n";
		o << "lane_width = " << fmt(h.lane_width) << "\n";
		o << "ego_lane = " << h.ego_lane << "\n";
		o << "num_landmarks = " << h.num_landmarks << "\n";
		o << "landmark_offset_min = " << fmt(h.landmark_offset_min) << "\n";
		o << "landmark_offset_max = " << fmt(h.landmark_offset_max) << "\n";
		o << "num_agents = " << h.agents.size() << "\n";
		dumpAgent(o, h.ego, true);
		for (const auto& a : h.agents) dumpAgent(o, a, false);
	}
	else
	{
		detail::dumpGenerated(o, generated);
	}
	dumpEffects(o, effects);
	detail::dumpObjectMotion(o, object_motion);
}
}  // namespace dynslam::sim
