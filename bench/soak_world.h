#pragma once
/** @file soak_world.h
 * The world of the soak benchmark (BM_Soak) and of the bounded-bookkeeping tests: what a real
 * front-end does to the readings over hours, streamed step by step (nothing stored, so the
 * peak memory of a run is the filter's). Header only; used by bench/ and tests/.
 *  - A ring of `landmarks` static landmarks the ego drives round lap after lap (the world in
 *    view does not change with the length of the run). Track breaks: every lap gives every
 *    landmark a new ID (the front-end lost it while it was out of view), so the map grows by a
 *    lap's landmarks per lap unless the filter drops what it does not see any more.
 *  - Missed detections: each true reading is dropped with `missed_probability`.
 *  - Clutter: `clutter_per_step` false readings per step, uniform in the sensor's disc, each with
 *    a fresh static ID (a one-reading track).
 *  - Objects: `objects` in convoy with the ego (rigid, turning slowly in their own frame); each
 *    is replaced by a new object (new object ID, the front-end's track break) every
 *    `object_lifetime` steps, so objects keep disappearing for good.
 * Deterministic given the seed; the random draws of an effect are made only if it is on. */
#include <dynslam/common/odometry_action.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <stdexcept>

#include "world_common.h"

namespace dynslam_bench
{
struct TSoakOptions
{
	int landmarks = 300;       ///< on the ring, one every `spacing` metres
	double spacing = 4.0;      ///< metres of track per landmark
	double step_length = 2.0;  ///< metres driven per step
	double range = 30.0;       ///< sensor range [m]
	double missed_probability = 0.1;
	int clutter_per_step = 2;
	int objects = 4;
	int features_per_object = 3;
	int object_lifetime = 200;  ///< steps before an object is replaced by a new one (0: never)
	Eigen::Matrix3d Sigma_w = Eigen::Vector3d(1e-5, 1e-5, 1e-7).asDiagonal();
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Identity() * 1e-5;
	unsigned seed = 29;
};

class CSoakWorld
{
public:
	explicit CSoakWorld(const TSoakOptions& o) : m_o(o), m_rng(o.seed)
	{
		if (o.landmarks < 1 || o.objects < 0 || o.features_per_object < 1 ||
		    o.clutter_per_step < 0 || o.object_lifetime < 0)
			throw std::invalid_argument("CSoakWorld: bad counts");
		m_radius = o.landmarks * o.spacing / (2 * M_PI);
		const double dth = o.step_length / m_radius;
		m_u = Eigen::Vector3d(m_radius * std::sin(dth), m_radius * (1 - std::cos(dth)), dth);
		m_stepsPerLap = int(std::ceil(2 * M_PI / dth));
	}

	int step() const { return m_k; }
	const Eigen::Vector3d& truePose() const { return m_x; }
	/** The lap of step k (every landmark's ID changes from one lap to the next). */
	int lap() const { return m_k / m_stepsPerLap; }
	int stepsPerLap() const { return m_stepsPerLap; }
	/** Clutter IDs are kClutterBase, kClutterBase + 1, ... (landmark IDs stay below). */
	static constexpr int32_t kClutterBase = 50'000;
	/** Clutter readings written so far. */
	int32_t clutterReadings() const { return m_nextClutterId - kClutterBase; }

	/** Produces step k = step() (the action into pose k and the frame at pose k), then advances. */
	void next(mrpt::obs::CActionCollection::Ptr& act, mrpt::obs::CSensoryFrame::Ptr& sf)
	{
		Eigen::Vector3d um = Eigen::Vector3d::Zero();
		Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
		if (m_k > 0)
		{
			m_x = dynslam::models::composePose(m_x, m_u);
			for (int i = 0; i < 3; ++i) um[i] = m_u[i] + m_n(m_rng) * std::sqrt(m_o.Sigma_w(i, i));
			cov = m_o.Sigma_w;
		}
		act = dynslam::makeOdometryAction(um, cov);
		auto obs = makeObservation(m_o.range);
		// The IDs of this lap: landmark i is lap * landmarks + i (below kClutterBase); clutter
		// IDs count up from kClutterBase (fresh IDs, never reused).
		const int32_t lapBase = int32_t(lap()) * m_o.landmarks;
		if (lapBase + m_o.landmarks > kClutterBase)
			throw std::runtime_error("CSoakWorld: ran out of landmark IDs");
		const Eigen::Vector2d p = m_x.head<2>();
		for (int i = 0; i < m_o.landmarks; ++i)
			if ((landmark(i) - p).norm() <= m_o.range && !missed())
				add(*obs, lapBase + i, landmark(i));
		for (int a = 0; a < m_o.objects; ++a)
		{
			const Eigen::Vector3d body = convoyBody(m_x, a, m_k);
			const int gen = m_o.object_lifetime > 0 ? m_k / m_o.object_lifetime : 0;
			for (int f = 0; f < m_o.features_per_object; ++f)
				if (!missed())
					add(*obs, dynslam::ids::objectFeatureId(gen * m_o.objects + a, f),
					    convoyFeature(body, a, f));
		}
		std::uniform_real_distribution<double> u01(0.0, 1.0);
		for (int c = 0; c < m_o.clutter_per_step; ++c)
		{
			const double r = m_o.range * std::sqrt(1 - u01(m_rng));
			const double b = (2 * u01(m_rng) - 1) * M_PI;
			const Eigen::Vector2d fw =
			    dynslam::models::composePose(m_x,
			                                 Eigen::Vector3d(r * std::cos(b), r * std::sin(b), 0))
			        .head<2>();
			if (m_nextClutterId > dynslam::ids::kStaticMax)
				throw std::runtime_error("CSoakWorld: ran out of static IDs");
			add(*obs, m_nextClutterId++, fw);
		}
		sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		++m_k;
	}

private:
	Eigen::Vector2d landmark(int i) const { return ringLandmark(i, m_o.landmarks, m_radius); }
	bool missed()
	{
		return m_o.missed_probability > 0 &&
		       std::uniform_real_distribution<double>(0.0, 1.0)(m_rng) < m_o.missed_probability;
	}
	void add(mrpt::obs::CObservationBearingRange& obs, int32_t id, const Eigen::Vector2d& f)
	{
		addReading(obs, m_x, id, f, m_o.Sigma_v, m_rng, m_n);
	}

	TSoakOptions m_o;
	std::mt19937 m_rng;
	std::normal_distribution<double> m_n{0.0, 1.0};
	double m_radius = 0;
	Eigen::Vector3d m_u, m_x = Eigen::Vector3d::Zero();
	int m_stepsPerLap = 1;
	int32_t m_nextClutterId = kClutterBase;
	int m_k = 0;
};
}  // namespace dynslam_bench
