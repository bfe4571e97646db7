#pragma once
/** @file synthetic_world.h
 * A controlled, streaming scenario for the scaling benchmarks and the hardening tests (header
 * only; used by bench/ and tests/hardening/). Unlike the simulator's generated scenarios it
 * fixes what a scaling curve must hold constant:
 *  - Ring track: N static landmarks around a circle the ego drives on; the sensor reports the
 *    `max_visible` nearest landmarks in range (so the work per step is fixed while the state
 *    grows with N). With `first_step_sees_all`, step 0 reports every landmark, so the state
 *    holds all N landmarks after one step.
 *  - Straight track: an endless road with a landmark every `spacing` metres (IDs in order), so
 *    landmarks leave the range for good and the drop policies keep the state bounded.
 *  - M objects in convoy with the ego (each rigid, rotating slowly in its own frame, always
 *    visible), so every step augments M object poses.
 * Steps are generated on demand (nothing is stored), deterministic given the seed. */
#include <dynslam/common/odometry_action.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "world_common.h"

namespace dynslam_bench
{
struct TSyntheticOptions
{
	enum class Track
	{
		Ring,
		Straight
	} track = Track::Ring;
	int landmarks = 100;       ///< ring: number of landmarks (straight: unbounded)
	double spacing = 4.0;      ///< metres of track per landmark
	double step_length = 2.0;  ///< metres driven per step
	double range = 30.0;       ///< sensor range for static landmarks [m]
	int max_visible = 20;      ///< at most this many static landmarks per step (nearest first)
	bool first_step_sees_all = false;  ///< ring: step 0 reports all landmarks
	/** Straight: step 0 also reports this many landmarks (IDs 0..prebuilt-1) lying behind the
	 * start out of range for good (a pre-built map); the road's landmarks get the IDs after. */
	int prebuilt = 0;
	int objects = 0;
	int features_per_object = 3;
	Eigen::Matrix3d Sigma_w = Eigen::Vector3d(1e-5, 1e-5, 1e-7).asDiagonal();
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Identity() * 1e-5;  ///< Cartesian noise
	unsigned seed = 1;
};

class CSyntheticWorld
{
public:
	explicit CSyntheticWorld(const TSyntheticOptions& o) : m_o(o), m_rng(o.seed)
	{
		if (o.landmarks < 1 && o.track == TSyntheticOptions::Track::Ring)
			throw std::invalid_argument("CSyntheticWorld: ring needs landmarks >= 1");
		if (o.objects < 0 || o.objects > 900 || o.features_per_object < 1)
			throw std::invalid_argument("CSyntheticWorld: bad object counts");
		m_radius = std::max(60.0, o.landmarks * o.spacing / (2 * M_PI));
		if (o.track == TSyntheticOptions::Track::Ring)
			for (int i = 0; i < o.landmarks; ++i)
				m_ring.push_back(ringLandmark(i, o.landmarks, m_radius));
		const double dth = o.track == TSyntheticOptions::Track::Ring ? o.step_length / m_radius : 0;
		m_u = dth == 0
		          ? Eigen::Vector3d(o.step_length, 0, 0)
		          : Eigen::Vector3d(m_radius * std::sin(dth), m_radius * (1 - std::cos(dth)), dth);
		// Ring: start on the circle centred at (0, R), heading +x.
	}

	/** The ground-truth ego pose of the step about to be generated. */
	const Eigen::Vector3d& truePose() const { return m_x; }
	int step() const { return m_k; }

	/** Produces step k = step() (the action into pose k and the frame at pose k), then advances. */
	void next(mrpt::obs::CActionCollection::Ptr& act, mrpt::obs::CSensoryFrame::Ptr& sf)
	{
		Eigen::Vector3d um = Eigen::Vector3d::Zero();
		Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
		if (m_k > 0)
		{
			m_x = dynslam::models::composePose(m_x, m_u);
			um = m_u + gauss3(m_o.Sigma_w);
			cov = m_o.Sigma_w;
		}
		act = makeAction(um, cov);
		auto obs = makeObservation(m_o.range);
		// Static landmarks: nearest first, at most max_visible (all on step 0 if asked).
		m_cand.clear();
		const Eigen::Vector2d p = m_x.head<2>();
		if (m_o.track == TSyntheticOptions::Track::Ring)
		{
			for (int i = 0; i < int(m_ring.size()); ++i)
			{
				const double d = (m_ring[i] - p).norm();
				if (d <= m_o.range || (m_k == 0 && m_o.first_step_sees_all))
					m_cand.push_back({d, i});
			}
		}
		else
		{
			const int lo = std::max(0, int(std::floor((p.x() - m_o.range) / m_o.spacing)));
			const int hi = int(std::ceil((p.x() + m_o.range) / m_o.spacing));
			for (int i = lo; i <= hi; ++i)
			{
				if (i + m_o.prebuilt > dynslam::ids::kStaticMax)
					throw std::runtime_error("CSyntheticWorld: ran out of static landmark IDs");
				const double d = (straightLandmark(i) - p).norm();
				if (d <= m_o.range) m_cand.push_back({d, i});
			}
		}
		std::sort(m_cand.begin(), m_cand.end());
		size_t nmax =
		    (m_k == 0 && m_o.first_step_sees_all) ? m_cand.size() : size_t(m_o.max_visible);
		const bool ring = m_o.track == TSyntheticOptions::Track::Ring;
		for (size_t j = 0; j < m_cand.size() && j < nmax; ++j)
		{
			const int i = m_cand[j].second;
			add(*obs, ring ? i : i + m_o.prebuilt, ring ? m_ring[i] : straightLandmark(i));
		}
		if (!ring && m_k == 0)
			for (int j = 0; j < m_o.prebuilt; ++j)
				add(*obs, j, straightLandmark(-1 - int(std::ceil(m_o.range / m_o.spacing)) - j));
		// Objects in convoy: body pose = ego pose (+) offset, rotating slowly in place.
		for (int a = 0; a < m_o.objects; ++a)
		{
			const Eigen::Vector3d body = convoyBody(m_x, a, m_k);
			for (int f = 0; f < m_o.features_per_object; ++f)
				add(*obs, dynslam::ids::objectFeatureId(a, f), convoyFeature(body, a, f));
		}
		sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		++m_k;
	}

private:
	Eigen::Vector2d straightLandmark(int i) const
	{
		const double off = ((i % 2) ? 1.0 : -1.0) * (5.0 + 10.0 * ((i * 7919) % 101) / 100.0);
		return Eigen::Vector2d(i * m_o.spacing, off);
	}
	Eigen::Vector3d gauss3(const Eigen::Matrix3d& S)
	{
		Eigen::Vector3d e;
		for (int i = 0; i < 3; ++i) e[i] = m_n(m_rng) * std::sqrt(std::max(0.0, S(i, i)));
		return e;
	}
	void add(mrpt::obs::CObservationBearingRange& obs, int32_t id, const Eigen::Vector2d& f)
	{
		addReading(obs, m_x, id, f, m_o.Sigma_v, m_rng, m_n);
	}
	static mrpt::obs::CActionCollection::Ptr makeAction(const Eigen::Vector3d& u,
	                                                    const Eigen::Matrix3d& C)
	{
		return dynslam::makeOdometryAction(u, C);
	}

	TSyntheticOptions m_o;
	std::mt19937 m_rng;
	std::normal_distribution<double> m_n{0.0, 1.0};
	double m_radius = 0;
	std::vector<Eigen::Vector2d> m_ring;
	Eigen::Vector3d m_u, m_x = Eigen::Vector3d::Zero();
	std::vector<std::pair<double, int>> m_cand;
	int m_k = 0;
};
}  // namespace dynslam_bench
