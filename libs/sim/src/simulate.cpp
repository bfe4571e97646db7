/** @file simulate.cpp
 * Noisy odometry and range-bearing observations from the ground truth (see doc/simulator.md:
 * sensor model, noise conversion, draw order). */
#include <dynslam/common/detection_groups.h>
#include <dynslam/common/odometry_action.h>
#include <dynslam/common/rawlog_file_writer.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/scenario.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "effects.h"

namespace dynslam::sim
{
namespace
{
/** A square root L (L L^T = S) of a covariance: exact sqrt of the diagonal when S is diagonal
 * (the noise grid), Cholesky otherwise (throws if S is not positive definite). */
template <int N>
Eigen::Matrix<double, N, N> covSqrt(const Eigen::Matrix<double, N, N>& S, const char* what)
{
	const Eigen::Matrix<double, N, N> D = S.diagonal().asDiagonal();
	if (S == D)
	{
		if ((S.diagonal().array() < 0).any())
			throw std::invalid_argument(std::string(what) + ": negative variance");
		return S.diagonal().cwiseSqrt().asDiagonal();
	}
	Eigen::LLT<Eigen::Matrix<double, N, N>> llt(S);
	if (llt.info() != Eigen::Success)
		throw std::invalid_argument(std::string(what) + ": covariance is not positive definite");
	return llt.matrixL();
}

uint32_t seed32(uint64_t s)
{
	if (s > UINT32_MAX)
		throw std::invalid_argument("noise_seed " + std::to_string(s) + " > 4294967295");
	return uint32_t(s);
}

/** Simulates one step at a time; the draws happen in a fixed order: 3 for the odometry
 * (k >= 1), then 2 per measurement in the order of the observation. */
class CStepSimulator
{
public:
	CStepSimulator(const io::TGroundTruth& gt, const TScenarioOptions& o, uint64_t seed)
	    : m_gt(gt),
	      m_o(o),
	      m_rng(seed32(seed)),
	      m_Lw(covSqrt<3>(o.Sigma_w, "[Noise] sigma_w")),
	      m_Lv(covSqrt<2>(o.Sigma_v, "[Noise] sigma_v")),
	      m_cell(o.sensor_range),
	      m_effects(gt, o, seed32(seed))
	{
		gt.checkConsistent();
		if (gt.numSteps() != o.numSteps())
			throw std::invalid_argument(
			    "simulateMeasurements: ground truth and options disagree on steps");
		for (const auto& [id, p] : gt.landmarks)
			m_grid[cellKey(cellOf(p[0]), cellOf(p[1]))].push_back(id);
	}

	/** Step k: ACT_k (the noisy odometry increment), then SF_k (the readings); the noise draws
	 * in that order. */
	void step(size_t k, mrpt::obs::CActionCollection::Ptr& actOut,
	          mrpt::obs::CSensoryFrame::Ptr& sfOut)
	{
		const auto stamp = stepTimestamp(m_o, k);
		actOut = makeAction(k, stamp);
		auto obs = makeObservation(stamp);
		// The readings are taken from the sensor's pose (x itself for a sensor at the origin).
		const Eigen::Vector3d xs = models::sensorPoseInWorld(m_gt.ego[k], m_o.sensor_pose);
		measure(k, xs, *obs);
		// Issue 12's front-end effects (after every noise draw, from their own generator).
		if (m_o.effects.any()) m_effects.apply(k, *obs, m_truth);
		sfOut = makeFrame(obs);
	}

	/** Class ground truth of step k's readings (in the order of the observation). */
	const std::vector<io::TReadingClass>& truth() const { return m_truth; }

private:
	/** ACT_k: noisy increment into pose k (zero with zero covariance for k = 0); 3 draws. */
	mrpt::obs::CActionCollection::Ptr makeAction(size_t k, mrpt::Clock::time_point stamp)
	{
		Eigen::Vector3d u = Eigen::Vector3d::Zero();
		Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
		if (k > 0)
		{
			u = models::poseDifference(m_gt.ego[k], m_gt.ego[k - 1]);
			if (m_o.odometry_rate_bias != 0 || m_o.odometry_scale_error != 0)
			{  // a biased reading of the true increment (TScenarioOptions::odometry_rate_bias)
				u.head<2>() /= 1 - m_o.odometry_scale_error;
				u[2] += m_o.odometry_rate_bias * m_o.dt;
			}
			u += m_Lw * draw3();
			u[2] = models::wrapToPi(u[2]);
			cov = m_o.Sigma_w;
		}
		// The covariance travels with the file (makeOdometryMovement: not emOdometry, whose
		// covariance MRPT rebuilds from its default motion model when the rawlog is read).
		auto act = mrpt::obs::CActionCollection::Create();
		act->insert(makeOdometryMovement(u, cov, stamp));
		return act;
	}

	/** SF_k's bearing-range observation without readings: the sensor's description. */
	mrpt::obs::CObservationBearingRange::Ptr makeObservation(mrpt::Clock::time_point stamp) const
	{
		auto obs = mrpt::obs::CObservationBearingRange::Create();
		obs->sensorLabel = m_o.sensor_label;
		obs->timestamp = stamp;
		obs->minSensorDistance = 0;
		obs->maxSensorDistance = float(m_o.sensor_range);
		obs->fieldOfView_yaw = float(2 * M_PI);
		obs->validCovariances = false;
		obs->sensor_std_range = float(m_o.std_range);
		obs->sensor_std_yaw = float(m_o.std_yaw);
		obs->sensor_std_pitch = 0;
		const Eigen::Vector3d& sp = m_o.sensor_pose;
		// (Left at the default identity for 0: CPose3D(0, 0, 0, 0, 0, 0) holds -0 entries in its
		// rotation matrix, a different file.)
		if (!sp.isZero())
			obs->sensorLocationOnRobot = mrpt::poses::CPose3D(sp[0], sp[1], 0, sp[2], 0, 0);
		return obs;
	}

	/** m_ids: the static landmarks within the true range of the sensor at xs, by increasing ID. */
	void landmarksInRange(const Eigen::Vector3d& xs)
	{
		m_ids.clear();
		const long cx = cellOf(xs[0]), cy = cellOf(xs[1]);
		for (long i = cx - 1; i <= cx + 1; ++i)
			for (long j = cy - 1; j <= cy + 1; ++j)
			{
				const auto it = m_grid.find(cellKey(i, j));
				if (it == m_grid.end()) continue;
				for (int32_t id : it->second)
					if ((m_gt.landmarks.at(id) - xs.head<2>()).norm() <= m_o.sensor_range)
						m_ids.push_back(id);
			}
		std::sort(m_ids.begin(), m_ids.end());
	}

	/** The readings of step k from the sensor pose xs (2 draws each, static landmarks first)
	 * and their class truth (m_truth). */
	void measure(size_t k, const Eigen::Vector3d& xs, mrpt::obs::CObservationBearingRange& obs)
	{
		landmarksInRange(xs);
		// At most this many readings: the vector is grown once (the sweep of the Monte Carlo
		// app simulates 225 runs of 121 steps).
		size_t readings = m_ids.size();
		for (const io::TObjectGroundTruth& og : m_gt.objects) readings += size_t(og.num_features);
		obs.sensedData.reserve(readings);
		m_truth.clear();
		for (int32_t id : m_ids)
			if (addMeasurement(obs, xs, m_gt.landmarks.at(id), id))
				addTruth(k, id, io::TrueClass::Static, -1, id);
		// Objects whose centroid is within range of the robot (ground truth's `visible`): all
		// their features.
		for (const io::TObjectGroundTruth& og : m_gt.objects)
			if (og.visible[k])
			{
				const io::TrueClass c = m_o.objectMovingAt(size_t(og.object), m_o.stepTime(k))
				                            ? io::TrueClass::Moving
				                            : io::TrueClass::Static;
				for (int j = 0; j < og.num_features; ++j)
				{
					const int32_t id = ids::objectFeatureId(og.object, j);
					if (addMeasurement(obs, xs, og.features[k].col(j), id))
						addTruth(k, id, c, og.object, j);
				}
			}
	}

	/** SF_k: the observation and, with detection groups, the box ID of every object reading
	 * (moving or parked): its object index. */
	mrpt::obs::CSensoryFrame::Ptr makeFrame(const mrpt::obs::CObservationBearingRange::Ptr& obs)
	{
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		if (m_o.effects.detection_groups)
		{
			std::vector<int32_t> ids, groups;
			for (size_t i = 0; i < obs->sensedData.size(); ++i)
			{
				ids.push_back(obs->sensedData[i].landmarkID);
				groups.push_back(m_truth.at(i).object);
			}
			sf->insert(makeDetectionGroups(ids, groups));
		}
		return sf;
	}

	Eigen::Vector3d draw3()
	{
		Eigen::Vector3d n;
		for (int i = 0; i < 3; ++i) n[i] = m_rng.drawGaussian1D_normalized();
		return n;
	}
	Eigen::Vector2d draw2()
	{
		const double a = m_rng.drawGaussian1D_normalized();
		const double b = m_rng.drawGaussian1D_normalized();
		return {a, b};
	}

	void addTruth(size_t k, int32_t id, io::TrueClass c, int32_t object, int32_t feature)
	{
		io::TReadingClass r;
		r.step = int(k);
		r.t = m_gt.t[k];
		r.index = int(m_truth.size());
		r.id = r.true_id = id;
		r.cls = c;
		r.object = object;
		r.feature = feature;
		m_truth.push_back(r);
	}

	/** Appends the noisy reading of f from the sensor's world pose xs; false if it was not
	 * added (a point at the sensor). */
	bool addMeasurement(mrpt::obs::CObservationBearingRange& obs, const Eigen::Vector3d& xs,
	                    const Eigen::Vector2d& f, int32_t id)
	{
		double range, yaw;
		if (m_o.noise_model == models::MeasurementModel::Cartesian)
		{
			const Eigen::Vector2d z = models::cartesianObserve(xs, f) + m_Lv * draw2();
			range = z.norm();
			if (!(range > 0)) return false;  // a point exactly at the sensor has no bearing
			yaw = std::atan2(z[1], z[0]);
		}
		else
		{
			const Eigen::Vector2d d = f - xs.head<2>();
			const Eigen::Vector2d n = draw2();
			range = d.norm() + m_o.std_range * n[0];
			yaw = std::atan2(d[1], d[0]) - xs[2] + m_o.std_yaw * n[1];
			if (range < 0) range = -range, yaw += M_PI;  // the same point
			yaw = models::wrapToPi(yaw);
		}
		mrpt::obs::CObservationBearingRange::TMeasurement m;
		m.range = float(range);
		m.yaw = float(yaw);
		m.pitch = 0;
		m.landmarkID = id;
		m.covariance.setZero();
		obs.sensedData.push_back(m);
		return true;
	}

	long cellOf(double v) const { return long(std::floor(v / m_cell)); }
	static uint64_t cellKey(long i, long j)
	{
		return (uint64_t(uint32_t(int32_t(i))) << 32) | uint32_t(int32_t(j));
	}

	const io::TGroundTruth& m_gt;
	const TScenarioOptions& m_o;
	mrpt::random::CRandomGenerator m_rng;
	Eigen::Matrix3d m_Lw;
	Eigen::Matrix2d m_Lv;
	double m_cell;
	std::unordered_map<uint64_t, std::vector<int32_t>> m_grid;
	std::vector<int32_t> m_ids;
	detail::CReadingEffects m_effects;
	std::vector<io::TReadingClass> m_truth;
};
}  // namespace

mrpt::Clock::time_point stepTimestamp(const TScenarioOptions& o, size_t k)
{
	return mrpt::Clock::fromDouble(o.start_time + o.stepTime(k));
}

TSimulatedRun simulateMeasurements(const io::TGroundTruth& gt, const TScenarioOptions& o,
                                   uint64_t noise_seed)
{
	CStepSimulator sim(gt, o, noise_seed);
	TSimulatedRun run;
	const size_t n = gt.numSteps();
	run.actions.resize(n);
	run.frames.resize(n);
	for (size_t k = 0; k < n; ++k)
	{
		sim.step(k, run.actions[k], run.frames[k]);
		run.classes.insert(run.classes.end(), sim.truth().begin(), sim.truth().end());
	}
	return run;
}

void writeRawlog(const TSimulatedRun& run, const std::string& path, const std::string& comment)
{
	if (run.actions.size() != run.frames.size())
		throw std::invalid_argument("writeRawlog: actions and frames differ in number");
	CRawlogFileWriter out(path, "writeRawlog");
	if (!comment.empty())
	{
		const auto stamp = run.frames.empty() || run.frames[0]->size() == 0
		                       ? mrpt::Clock::fromDouble(0)
		                       : (*run.frames[0]->begin())->timestamp;
		out.writeComment(comment, stamp);
	}
	for (size_t k = 0; k < run.actions.size(); ++k) out.writeStep(*run.actions[k], *run.frames[k]);
	out.close();
}

void simulateToRawlog(const io::TGroundTruth& gt, const TScenarioOptions& o, uint64_t noise_seed,
                      const std::string& path, const std::string& comment)
{
	CStepSimulator sim(gt, o, noise_seed);
	CRawlogFileWriter out(path, "simulateToRawlog");
	if (!comment.empty()) out.writeComment(comment, stepTimestamp(o, 0));
	mrpt::obs::CActionCollection::Ptr act;
	mrpt::obs::CSensoryFrame::Ptr sf;
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		sim.step(k, act, sf);
		out.writeStep(*act, *sf);
	}
	out.close();
}
}  // namespace dynslam::sim
