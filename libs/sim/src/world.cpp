/** @file world.cpp
 * The highway of Section V and generated scenarios as closed-form trajectories, and their
 * ground truth (see doc/simulator.md). */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/markov_motion.h>
#include <dynslam/sim/scenario.h>
#include <mrpt/random/RandomGenerators.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "truth_noise.h"

namespace dynslam::sim
{
namespace
{
TBodyMotion highwayMotion(const THighwayAgent& a, const THighwayOptions& h)
{
	TBodyMotion m;
	m.s0 = a.x0;
	// Issue 12: parked until start_moving_at_s, at rest from stop_at_s on (options validated
	// that no other change overlaps these ramps).
	const double d = a.start_stop_duration_s;
	std::vector<TRamp> sp = a.speed_changes;
	double v0 = a.speed;
	if (!std::isnan(a.start_moving_at_s))
	{
		v0 = 0;
		sp.insert(sp.begin(), TRamp{a.start_moving_at_s, d, a.speed});
	}
	if (!std::isnan(a.stop_at_s))
	{
		sp.push_back(TRamp{a.stop_at_s - d, d, 0.0});
		m.stop_time = a.stop_at_s;
		m.stop_heading_time = a.stop_at_s - d / 2;
	}
	m.speed = CSmoothProfile(v0, sp);
	if (a.kind == THighwayAgent::Kind::Car)
	{
		std::vector<TRamp> lat = a.lane_changes;
		for (TRamp& r : lat) r.target = h.laneY(int(r.target));
		m.lateral = CSmoothProfile(h.laneY(a.lane0), lat);
	}
	else
		m.lateral = CSmoothProfile(a.y0, a.lateral_moves);
	return m;
}

TWorld buildHighway(const TScenarioOptions& o)
{
	const THighwayOptions& h = o.highway;
	TWorld w;
	w.track.radius = 0;
	w.ego = highwayMotion(h.ego, h);
	for (const THighwayAgent& a : h.agents)
	{
		TWorld::TObject obj;
		obj.name = a.section;
		obj.motion = highwayMotion(a, h);
		if (a.kind == THighwayAgent::Kind::Car)
		{
			obj.kind = ObjectKind::Car;
			obj.body = carCorners(a.length, a.width);
		}
		else
		{
			obj.kind = ObjectKind::Pedestrian;
			obj.body = ellipsePoints(a.num_features, 0, a.width / 2);
		}
		w.objects.push_back(std::move(obj));
	}
	// Landmarks: x uniform along the road, alternately left and right of it, at a uniform
	// distance from the road edge.
	mrpt::random::CRandomGenerator rng(o.world_seed);
	for (int i = 0; i < h.num_landmarks; ++i)
	{
		const double x = rng.drawUniform(0.0, h.length);
		const double off = rng.drawUniform(h.landmark_offset_min, h.landmark_offset_max);
		const double y = (i % 2 == 0) ? h.roadLeft() + off : h.roadRight() - off;
		if (!o.inLandmarkGap(x)) w.landmarks.emplace(int32_t(i), Eigen::Vector2d(x, y));
	}
	return w;
}

/** -1 or +1 with equal probability (one uniform draw). */
double randomSide(mrpt::random::CRandomGenerator& rng)
{
	return rng.drawUniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
}

/** The speed ramps of a car's hard brakes (TGeneratedOptions::car_brakes; none if 0). A
 * smoothstep ramp of duration D from v to f v has a peak deceleration 1.5 v (1 - f) / D. */
std::vector<TRamp> brakeRamps(const TGeneratedOptions& g, double v, double T,
                              mrpt::random::CRandomGenerator& rng)
{
	std::vector<TRamp> r;
	if (g.car_brakes <= 0 || !(v > 0)) return r;
	const double f = g.car_brake_speed_factor, hold = 2.0;
	const double D = 1.5 * v * (1 - f) / g.car_brake_decel, span = 2 * D + hold;
	const double slot = T / g.car_brakes;
	if (slot < span)
		throw std::invalid_argument("[Generated] car_brakes = " + std::to_string(g.car_brakes) +
		                            ": a brake takes " + std::to_string(span) +
		                            " s, more than the run's " + std::to_string(slot) +
		                            " s per brake");
	for (int i = 0; i < g.car_brakes; ++i)
	{
		const double t0 = i * slot + rng.drawUniform(0.0, slot - span);
		r.push_back({t0, D, f * v});
		r.push_back({t0 + D + hold, D, v});
	}
	return r;
}

/** Cars: in a lane other than the ego's (lane centres at +-j lane_width), around the ego,
 * speed ego_speed * factor with a +-10% sine variation (period 20-60 s), weaving by up to
 * a quarter lane (period 10-30 s). */
void addCars(TWorld& w, const TGeneratedOptions& g, double T, uint32_t brakeSeed,
             mrpt::random::CRandomGenerator& rng)
{
	mrpt::random::CRandomGenerator brakeRng(brakeSeed);  // private: rng's draws unchanged
	auto side = [&]() { return randomSide(rng); };
	const int sideLanes = std::max(1, (g.num_lanes - 1) / 2);
	for (int i = 0; i < g.num_cars; ++i)
	{
		TWorld::TObject obj;
		obj.kind = ObjectKind::Car;
		obj.name = "car" + std::to_string(i);
		const double s0 = rng.drawUniform(-g.object_spread, g.object_spread);
		const int lane = 1 + int(rng.drawUniform(0.0, double(sideLanes) - 1e-9));
		const double d0 = side() * lane * g.lane_width;
		const double v =
		    g.ego_speed * rng.drawUniform(g.car_speed_factor_min, g.car_speed_factor_max);
		const double wv = 2 * M_PI / rng.drawUniform(20.0, 60.0),
		             wl = 2 * M_PI / rng.drawUniform(10.0, 30.0);
		obj.motion.s0 = s0;
		obj.motion.speed = CSmoothProfile(v, brakeRamps(g, v, T, brakeRng), 0.1 * v, wv,
		                                  rng.drawUniform(0.0, 2 * M_PI));
		obj.motion.lateral = CSmoothProfile(d0, {}, rng.drawUniform(0.0, 0.25 * g.lane_width), wl,
		                                    rng.drawUniform(0.0, 2 * M_PI));
		obj.body = g.features_per_car == 4
		               ? carCorners(g.car_length, g.car_width)
		               : ellipsePoints(g.features_per_car, g.car_length / 2, g.car_width / 2);
		w.objects.push_back(std::move(obj));
	}
}

TWorld buildGenerated(const TScenarioOptions& o)
{
	const TGeneratedOptions& g = o.generated;
	TWorld w;
	w.track.radius = g.track_radius;
	w.ego.s0 = 0;
	w.ego.speed = CSmoothProfile(g.ego_speed, {});
	w.ego.lateral = CSmoothProfile(0, {});
	mrpt::random::CRandomGenerator rng(o.world_seed);
	const double T = o.stepTime(o.numSteps() - 1);
	const double pathLength = g.ego_speed * T;
	const bool circle = g.track_radius > 0;
	const double trackLength = circle ? 2 * M_PI * g.track_radius : pathLength + 2 * o.sensor_range;
	const double trackStart = circle ? 0 : -o.sensor_range;
	auto side = [&]() { return randomSide(rng); };

	// Landmarks: uniform along the track (the ego's whole path plus the sensor range on a
	// straight track, the whole circle otherwise), at a uniform offset on either side.
	for (int i = 0; i < g.num_landmarks; ++i)
	{
		const double s = trackStart + rng.drawUniform(0.0, trackLength);
		const double d = side() * rng.drawUniform(g.landmark_offset_min, g.landmark_offset_max);
		if (!o.inLandmarkGap(s)) w.landmarks.emplace(int32_t(i), w.track.point(s, d));
	}
	addCars(w, g, T, o.world_seed ^ 0x5BD1E995u, rng);
	// Pedestrians: cross the road back and forth (d = D sin(w t + phi), D = half the road plus
	// 2 m, peak speed pedestrian_speed) while drifting 0.3 m/s along it, placed along the
	// ego's path.
	const double D = 0.5 * g.num_lanes * g.lane_width + 2.0;
	for (int i = 0; i < g.num_pedestrians; ++i)
	{
		TWorld::TObject obj;
		obj.kind = ObjectKind::Pedestrian;
		obj.name = "pedestrian" + std::to_string(i);
		obj.motion.s0 = circle ? rng.drawUniform(0.0, trackLength)
		                       : rng.drawUniform(-g.object_spread, pathLength + g.object_spread);
		obj.motion.speed = CSmoothProfile(0.3 * side(), {});
		obj.motion.lateral =
		    CSmoothProfile(0, {}, D, g.pedestrian_speed / D, rng.drawUniform(0.0, 2 * M_PI));
		obj.body = ellipsePoints(g.features_per_pedestrian, g.pedestrian_width / 2,
		                         g.pedestrian_width / 2);
		w.objects.push_back(std::move(obj));
	}
	// Rotating objects: fixed beside the road (like the landmarks), spinning at a constant
	// yaw rate with |rate| uniform in [0.1, yaw_rate_max] rad/s.
	for (int i = 0; i < g.num_rotating; ++i)
	{
		TWorld::TObject obj;
		obj.kind = ObjectKind::Rotating;
		obj.name = "rotating" + std::to_string(i);
		obj.motion.s0 = circle ? rng.drawUniform(0.0, trackLength)
		                       : rng.drawUniform(-g.object_spread, pathLength + g.object_spread);
		obj.motion.speed = CSmoothProfile(0, {});
		obj.motion.lateral =
		    CSmoothProfile(side() * rng.drawUniform(D, D + g.landmark_offset_min + 5.0), {});
		obj.motion.spin = true;
		obj.motion.heading0 = rng.drawUniform(-M_PI, M_PI);
		obj.motion.yaw_rate =
		    side() * rng.drawUniform(std::min(0.1, g.yaw_rate_max), g.yaw_rate_max);
		obj.body = ellipsePoints(g.features_per_rotating, g.rotating_radius, g.rotating_radius);
		w.objects.push_back(std::move(obj));
	}
	return w;
}
/** The Markov-switching truth (markov_motion.h; empty unless [ObjectMotion] model = markov):
 * per object and step its world features g(xi_k, F_0), xi_k relative to step 0, starting with
 * the scripted motion's rate at t = 0 (a forward difference over 1e-6 s of the closed form). */
std::vector<std::vector<Eigen::Matrix2Xd>> markovFeatures(const TWorld& w,
                                                          const TScenarioOptions& o)
{
	if (!o.object_motion.markov) return {};
	const double eps = 1e-6;
	std::vector<Eigen::VectorXd> s0;
	std::vector<Eigen::Matrix2Xd> F0;
	for (const TWorld::TObject& obj : w.objects)
	{
		F0.push_back(bodyToWorld(obj.motion.pose(w.track, 0.0), obj.body));
		const Eigen::Matrix2Xd F1 = bodyToWorld(obj.motion.pose(w.track, eps), obj.body);
		const bool translationOnly = obj.body.cols() == 1;
		Eigen::VectorXd s = Eigen::VectorXd::Zero(translationOnly ? 4 : 6);
		if (translationOnly)
			s.tail<2>() = (F1.col(0) - F0.back().col(0)) / eps;
		else
			s.tail<3>() = models::objectPoseInverse(F0.back(), F1) / eps;
		s0.push_back(s);
	}
	const std::vector<TMarkovTrack> tracks = markovObjectTracks(o, s0);
	std::vector<std::vector<Eigen::Matrix2Xd>> out(tracks.size());
	for (size_t i = 0; i < tracks.size(); ++i)
		for (const Eigen::VectorXd& s : tracks[i].state)
		{
			const Eigen::Index d = s.size() / 2;
			out[i].push_back(d == 2 ? Eigen::Matrix2Xd(F0[i].colwise() + s.head<2>())
			                        : detail::offsetFeatures(F0[i], s.head<3>()));
		}
	return out;
}
}  // namespace

TWorld buildWorld(const TScenarioOptions& o)
{
	o.validate();
	return o.type == ScenarioType::Highway ? buildHighway(o) : buildGenerated(o);
}

io::TGroundTruth buildGroundTruth(const TScenarioOptions& o)
{
	return groundTruthFromWorld(buildWorld(o), o);
}

io::TGroundTruth groundTruthFromWorld(const TWorld& w, const TScenarioOptions& o)
{
	const size_t n = o.numSteps();
	const double nan = std::numeric_limits<double>::quiet_NaN();
	io::TGroundTruth gt;
	gt.t.resize(n);
	gt.ego.resize(n);
	// The model-matched truth (truth_noise.h; off by default: x0 = 0, no offsets): the whole
	// world is moved by the drawn start pose x0, the objects' poses get CV offsets first.
	const Eigen::Vector3d x0 = detail::trueStartPose(o);
	const bool moved = !x0.isZero();
	const auto offsets = detail::objectPoseOffsets(o, w.objects.size());
	const auto markov = markovFeatures(w, o);
	gt.landmarks = w.landmarks;
	if (moved)
		for (auto& [id, p] : gt.landmarks) p = bodyToWorld(x0, p);
	for (size_t k = 0; k < n; ++k)
	{
		// The rawlog's time stamps (start_time + k dt, as stepTimestamp() writes them), so that
		// the ground-truth files and the apps' trajectories share one time base.
		gt.t[k] = o.start_time + o.stepTime(k);
		gt.ego[k] = w.ego.pose(w.track, o.stepTime(k));
		if (moved) gt.ego[k] = models::composePose(x0, gt.ego[k]);
	}
	gt.objects.resize(w.objects.size());
	for (size_t i = 0; i < w.objects.size(); ++i)
	{
		const TWorld::TObject& obj = w.objects[i];
		io::TObjectGroundTruth& og = gt.objects[i];
		og.object = int32_t(i);
		og.num_features = int(obj.body.cols());
		og.features.resize(n);
		og.pose.assign(n, Eigen::Vector3d::Constant(nan));
		og.visible.assign(n, 0);
		for (size_t k = 0; k < n; ++k)
		{
			Eigen::Matrix2Xd F =
			    markov.empty() ? bodyToWorld(obj.motion.pose(w.track, o.stepTime(k)), obj.body)
			                   : markov[i][k];
			if (!offsets.empty()) F = detail::offsetFeatures(F, offsets[i][k]);
			if (moved) F = bodyToWorld(x0, F);
			og.features[k] = F;
			// The sensor reports an object as a whole when its centroid is within range.
			const Eigen::Vector2d c = F.rowwise().mean();
			og.visible[k] = (c - gt.ego[k].head<2>()).norm() <= o.sensor_range ? 1 : 0;
			if (og.visible[k] && og.first_step < 0) og.first_step = int(k);
			if (og.first_step >= 0)
			{
				const Eigen::Matrix2Xd& F0 = og.features[og.first_step];
				if (og.translationOnly())
					og.pose[k] << models::objectTranslationInverse(F0.col(0), F.col(0)), 0.0;
				else
					og.pose[k] = models::objectPoseInverse(F0, F);
			}
		}
	}
	gt.checkConsistent();
	return gt;
}
}  // namespace dynslam::sim
