#pragma once
/** A small self-contained scenario for the filter tests: an ego on a circle, random static
 * landmarks, objects translating and rotating, a range-limited all-around sensor. Seeded. */
#include <dynslam/common/odometry_action.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Eigenvalues>
#include <map>
#include <random>
#include <vector>

namespace dynslam_test
{
struct TinyScenarioOptions
{
	int steps = 30;
	int landmarks = 12;
	int objects = 0;
	int features_per_object = 3;
	double range = 12.0;
	Eigen::Vector3d u = Eigen::Vector3d(0.5, 0.0, 0.05);  ///< true increment per step
	Eigen::Matrix3d Sigma_w = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	bool cartesian_noise = false;  ///< false: range-bearing noise with Sigma_rb
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Identity() * 1e-4;         ///< Cartesian noise
	Eigen::Matrix2d Sigma_rb = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();  ///< range-bearing noise
	unsigned seed = 1;
	bool noise = true;
	double object_turn_rate = 0.03;  ///< object a turns by (a + 1) times this per step [rad]
	/** false: the objects' centres translate at constant velocity (the body rotates about it);
	 * true: the centre's velocity turns with the body (constant turn rate and velocity: the
	 * centre moves on a circle of radius |v| / turn rate). */
	bool objects_on_arcs = false;
	/** The sensor's pose on the robot (x, y, yaw), written to sensorLocationOnRobot (with
	 * height sensor_z); readings are taken from x (+) sensor. */
	Eigen::Vector3d sensor = Eigen::Vector3d::Zero();
	double sensor_z = 0;
};

struct TinyScenario
{
	std::vector<mrpt::obs::CActionCollection::Ptr> actions;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	std::vector<Eigen::Vector3d> ego;
	std::map<int32_t, Eigen::Vector2d> landmarks;
};

inline Eigen::VectorXd gaussian(std::mt19937& g, const Eigen::MatrixXd& S)
{
	std::normal_distribution<double> n(0, 1);
	Eigen::VectorXd e(S.rows());
	for (int i = 0; i < e.size(); ++i) e[i] = n(g);
	const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S);
	return es.eigenvectors() * es.eigenvalues().cwiseMax(0).cwiseSqrt().asDiagonal() * e;
}

inline mrpt::obs::CActionCollection::Ptr makeAction(const Eigen::Vector3d& u,
                                                    const Eigen::Matrix3d& C)
{
	return dynslam::makeOdometryAction(u, C);
}

/** An object of the tiny scenario: centre, velocity, rotation rate, rigid feature offsets. */
struct TinyObject
{
	Eigen::Vector2d c, v;
	double w;
	Eigen::Matrix2Xd off;
};

inline std::vector<TinyObject> makeTinyObjects(const TinyScenarioOptions& o, std::mt19937& g,
                                               std::uniform_real_distribution<double>& U)
{
	std::vector<TinyObject> objs;
	for (int a = 0; a < o.objects; ++a)
	{
		TinyObject ob;
		ob.c = Eigen::Vector2d(U(g) * 0.5, 10 + U(g) * 0.5);
		ob.v = Eigen::Vector2d(0.2 + 0.1 * a, -0.1);
		ob.w = o.object_turn_rate * (a + 1);
		ob.off.resize(2, o.features_per_object);
		for (int k = 0; k < o.features_per_object; ++k)
			ob.off.col(k) =
			    Eigen::Vector2d(std::cos(2.1 * k + a), std::sin(2.1 * k + a)) * (0.8 + 0.2 * k);
		objs.push_back(ob);
	}
	return objs;
}

inline TinyScenario makeTinyScenario(const TinyScenarioOptions& o)
{
	using namespace dynslam;
	std::mt19937 g(o.seed);
	std::uniform_real_distribution<double> U(-14, 14);
	TinyScenario sc;
	for (int i = 0; i < o.landmarks; ++i) sc.landmarks[i] = Eigen::Vector2d(U(g), U(g) + 10);
	const std::vector<TinyObject> objs = makeTinyObjects(o, g, U);
	Eigen::Vector3d x = Eigen::Vector3d::Zero();
	for (int k = 0; k < o.steps; ++k)
	{
		Eigen::Vector3d meas_u = Eigen::Vector3d::Zero();
		Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
		if (k > 0)
		{
			x = models::composePose(x, o.u);
			meas_u =
			    o.u + (o.noise ? Eigen::Vector3d(gaussian(g, o.Sigma_w)) : Eigen::Vector3d::Zero());
			cov = o.Sigma_w;
		}
		sc.ego.push_back(x);
		sc.actions.push_back(makeAction(meas_u, cov));
		auto obs = mrpt::obs::CObservationBearingRange::Create();
		obs->sensorLabel = "RB";
		obs->maxSensorDistance = float(o.range);
		obs->fieldOfView_yaw = float(2 * M_PI);
		obs->sensorLocationOnRobot =
		    mrpt::poses::CPose3D(o.sensor[0], o.sensor[1], o.sensor_z, o.sensor[2], 0, 0);
		const Eigen::Vector3d xs = models::sensorPoseInWorld(x, o.sensor);  // == x for s = 0
		auto add = [&](int32_t id, const Eigen::Vector2d& f)
		{
			Eigen::Vector2d rb;
			if (o.cartesian_noise)
			{
				Eigen::Vector2d z = models::cartesianObserve(xs, f);
				if (o.noise) z += gaussian(g, o.Sigma_v);
				rb = models::cartesianToRangeBearing(z);
			}
			else
			{
				rb = models::rangeBearingObserve(xs, f);
				if (o.noise) rb += gaussian(g, o.Sigma_rb);
			}
			mrpt::obs::CObservationBearingRange::TMeasurement m;
			m.range = float(rb[0]);
			m.yaw = float(models::wrapToPi(rb[1]));
			m.pitch = 0;
			m.landmarkID = id;
			obs->sensedData.push_back(m);
		};
		for (const auto& [id, f] : sc.landmarks)
			if ((f - x.head<2>()).norm() <= o.range) add(id, f);
		for (int a = 0; a < int(objs.size()); ++a)
		{
			const TinyObject& ob = objs[a];
			Eigen::Vector2d c = ob.c + ob.v * k;
			if (o.objects_on_arcs && ob.w != 0)
			{
				const double a = ob.w * k;
				c = ob.c + (Eigen::Matrix2d() << std::sin(a), std::cos(a) - 1, 1 - std::cos(a),
				            std::sin(a))
				                   .finished() *
				               ob.v / ob.w;
			}
			if ((c - x.head<2>()).norm() > o.range) continue;
			const Eigen::Matrix2d R = models::rot2(ob.w * k);
			for (int f = 0; f < ob.off.cols(); ++f)
				add(ids::objectFeatureId(a, f), c + R * ob.off.col(f));
		}
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		sc.frames.push_back(sf);
	}
	return sc;
}
/** Two objects of three features among the default landmarks, Cartesian noise: the scenario of
 * the seam and module tests. */
inline TinyScenario makeTwoObjectScenario(int steps, unsigned seed)
{
	TinyScenarioOptions o;
	o.objects = 2;
	o.cartesian_noise = true;
	o.steps = steps;
	o.seed = seed;
	return makeTinyScenario(o);
}
}  // namespace dynslam_test
