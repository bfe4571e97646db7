/** Measurement models with the sensor not at the robot's origin (measurement.h,
 * *FromSensor): every Jacobian (w.r.t. ego, feature / measurement, sensor pose) vs central
 * differences at seeded random states and at the +-pi wrap of the ego heading and of the
 * sensor's world heading; the identity sensor pose reproduces the sensor-at-origin functions
 * bit for bit; an independent two-frame formula gives the same values; round trips; a
 * non-finite sensor pose throws. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core_test_utils.h"

using namespace dynslam::models;
using core_test::checkJacobian;
using dynslam_test::uniform;
using Eigen::VectorXd;

namespace
{
constexpr int kRandomStates = 60;
const MeasurementModel kModels[] = {MeasurementModel::Cartesian, MeasurementModel::RangeBearing};

struct TState
{
	Eigen::Vector3d x, s;
};

/** Random ego and sensor poses, then ego headings at the wrap (with a sensor yaw of 0 and of
 * +-pi/2), then sensor yaws that put the sensor's world heading exactly at +-pi. */
std::vector<TState> testStates()
{
	std::vector<TState> v;
	auto randomSensor = []
	{ return Eigen::Vector3d(uniform(-2, 2), uniform(-2, 2), uniform(-M_PI, M_PI)); };
	for (int i = 0; i < kRandomStates; ++i) v.push_back({core_test::randomPose(), randomSensor()});
	for (double th : core_test::wrapHeadings())
		for (double yaw : {0.0, M_PI / 2, -M_PI / 2})
			v.push_back({Eigen::Vector3d(uniform(-50, 50), uniform(-50, 50), th),
			             Eigen::Vector3d(uniform(-2, 2), uniform(-2, 2), yaw)});
	for (double th : {0.3, -2.0})
		v.push_back({Eigen::Vector3d(1, 2, th), Eigen::Vector3d(0.3, -0.1, M_PI - th)});
	return v;
}

/** A point at distance r in [1, 40] and bearing b from the sensor's world pose. */
Eigen::Vector2d pointFromSensor(const TState& st, double b)
{
	const Eigen::Vector3d xs = sensorPoseInWorld(st.x, st.s);
	const double r = uniform(1, 40);
	return xs.head<2>() + r * Eigen::Vector2d(std::cos(xs[2] + b), std::sin(xs[2] + b));
}

/** The sensor-frame Cartesian reading, computed through the two frames without the library:
 * robot frame first (R(theta)^T (f - p)), then the sensor frame (R(yaw_s)^T (. - t_s)). */
Eigen::Vector2d twoFrameCartesian(const TState& st, const Eigen::Vector2d& f)
{
	const Eigen::Vector2d inRobot = rot2(st.x[2]).transpose() * (f - st.x.head<2>());
	return rot2(st.s[2]).transpose() * (inRobot - st.s.head<2>());
}
}  // namespace

TEST(SensorPoseJacobians, ObserveAndInverseBothModels)
{
	dynslam_test::rng(301);
	double worst = 0;
	for (MeasurementModel m : kModels)
	{
		const std::vector<int> zAngle =
		    m == MeasurementModel::RangeBearing ? std::vector<int>{1} : std::vector<int>{};
		for (const TState& st : testStates())
			for (double b : {uniform(-M_PI, M_PI), M_PI - 1e-9, -M_PI + 1e-9})
			{
				const Eigen::Vector2d f = pointFromSensor(st, b);
				Matrix23d J_z_x, J_z_s;
				Eigen::Matrix2d J_z_f;
				const Eigen::Vector2d z =
				    observeFromSensor(m, st.x, st.s, f, &J_z_x, &J_z_f, &J_z_s);
				auto h = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& s,
				             const Eigen::Vector2d& p)
				{ return VectorXd(observeFromSensor(m, x, s, p)); };
				EXPECT_TRUE(checkJacobian(
				    J_z_x, [&](const VectorXd& v) { return h(v, st.s, f); }, st.x, zAngle, worst))
				    << "J_z_x " << toString(m);
				EXPECT_TRUE(checkJacobian(
				    J_z_f, [&](const VectorXd& v) { return h(st.x, st.s, v); }, f, zAngle, worst))
				    << "J_z_f " << toString(m);
				EXPECT_TRUE(checkJacobian(
				    J_z_s, [&](const VectorXd& v) { return h(st.x, v, f); }, st.s, zAngle, worst))
				    << "J_z_s " << toString(m);

				Matrix23d J_f_x, J_f_s;
				Eigen::Matrix2d J_f_z;
				inverseObserveFromSensor(m, st.x, st.s, z, &J_f_x, &J_f_z, &J_f_s);
				auto l = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& s,
				             const Eigen::Vector2d& q)
				{ return VectorXd(inverseObserveFromSensor(m, x, s, q)); };
				EXPECT_TRUE(checkJacobian(
				    J_f_x, [&](const VectorXd& v) { return l(v, st.s, z); }, st.x, {}, worst))
				    << "J_f_x " << toString(m);
				EXPECT_TRUE(checkJacobian(
				    J_f_z, [&](const VectorXd& v) { return l(st.x, st.s, v); }, z, {}, worst))
				    << "J_f_z " << toString(m);
				EXPECT_TRUE(checkJacobian(
				    J_f_s, [&](const VectorXd& v) { return l(st.x, v, z); }, st.s, {}, worst))
				    << "J_f_s " << toString(m);
			}
	}
	core_test::reportWorst("observe/inverse from a sensor pose", worst);
}

TEST(SensorPoseJacobians, SensorPoseInWorld)
{
	dynslam_test::rng(302);
	double worst = 0;
	for (const TState& st : testStates())
	{
		Eigen::Matrix3d J_xs_x, J_xs_s;
		sensorPoseInWorld(st.x, st.s, &J_xs_x, &J_xs_s);
		EXPECT_TRUE(checkJacobian(
		    J_xs_x, [&](const VectorXd& v) { return VectorXd(sensorPoseInWorld(v, st.s)); }, st.x,
		    {2}, worst));
		EXPECT_TRUE(checkJacobian(
		    J_xs_s, [&](const VectorXd& v) { return VectorXd(sensorPoseInWorld(st.x, v)); }, st.s,
		    {2}, worst));
	}
	core_test::reportWorst("sensorPoseInWorld", worst);
}

TEST(SensorPose, IdentityReproducesTheOriginModelsExactly)
{
	dynslam_test::rng(303);
	const Eigen::Vector3d s0 = Eigen::Vector3d::Zero();
	int compared = 0;
	for (MeasurementModel m : kModels)
		for (const TState& st : testStates())
		{
			const Eigen::Vector2d f = pointFromSensor({st.x, s0}, uniform(-M_PI, M_PI));
			Matrix23d A_x, B_x, J_z_s;
			Eigen::Matrix2d A_f, B_f;
			const Eigen::Vector2d za = observe(m, st.x, f, &A_x, &A_f);
			const Eigen::Vector2d zb = observeFromSensor(m, st.x, s0, f, &B_x, &B_f, &J_z_s);
			// Bit for bit: operator== on the Eigen objects, not a tolerance.
			EXPECT_TRUE(za == zb) << toString(m) << ": " << za.transpose() << " vs "
			                      << zb.transpose();
			EXPECT_TRUE(A_x == B_x) << toString(m) << "\n" << A_x << "\nvs\n" << B_x;
			EXPECT_TRUE(A_f == B_f) << toString(m);

			Matrix23d C_x, D_x;
			Eigen::Matrix2d C_z, D_z;
			const Eigen::Vector2d fa = inverseObserve(m, st.x, za, &C_x, &C_z);
			const Eigen::Vector2d fb = inverseObserveFromSensor(m, st.x, s0, za, &D_x, &D_z);
			EXPECT_TRUE(fa == fb) << toString(m);
			EXPECT_TRUE(C_x == D_x) << toString(m);
			EXPECT_TRUE(C_z == D_z) << toString(m);
			++compared;
		}
	EXPECT_EQ(compared, 2 * int(testStates().size()));
}

TEST(SensorPose, MatchesTheTwoFrameFormulaAndRoundTrips)
{
	dynslam_test::rng(304);
	double worstValue = 0, worstRoundTrip = 0;
	for (const TState& st : testStates())
	{
		const Eigen::Vector2d f = pointFromSensor(st, uniform(-M_PI, M_PI));
		const Eigen::Vector2d c = twoFrameCartesian(st, f);
		const Eigen::Vector2d zc = cartesianObserveFromSensor(st.x, st.s, f);
		const Eigen::Vector2d zrb = rangeBearingObserveFromSensor(st.x, st.s, f);
		worstValue = std::max(worstValue, (zc - c).norm());
		worstValue = std::max(worstValue, std::abs(zrb[0] - c.norm()));
		worstValue = std::max(worstValue, std::abs(wrapToPi(zrb[1] - std::atan2(c[1], c[0]))));
		EXPECT_LE(zrb[1], M_PI);
		EXPECT_GT(zrb[1], -M_PI);
		for (MeasurementModel m : kModels)
		{
			const Eigen::Vector2d back =
			    inverseObserveFromSensor(m, st.x, st.s, observeFromSensor(m, st.x, st.s, f));
			worstRoundTrip = std::max(worstRoundTrip, (back - f).norm());
		}
	}
	std::printf("[  worst   ] value vs two-frame formula %.3g, round trip %.3g\n", worstValue,
	            worstRoundTrip);
	EXPECT_LT(worstValue, 1e-12);
	EXPECT_LT(worstRoundTrip, 1e-12);
	// A sensor 0.3 m ahead of a robot at the origin heading +y sees a point at (0, 1.3) at
	// 1 m straight ahead; a sensor yawed by +90 deg sees it at bearing -90 deg.
	const Eigen::Vector3d x(0, 0, M_PI / 2);
	const Eigen::Vector2d z =
	    rangeBearingObserveFromSensor(x, Eigen::Vector3d(0.3, 0, 0), Eigen::Vector2d(0, 1.3));
	EXPECT_NEAR(z[0], 1.0, 1e-14);
	EXPECT_NEAR(z[1], 0.0, 1e-14);
	const Eigen::Vector2d zy =
	    rangeBearingObserveFromSensor(x, Eigen::Vector3d(0, 0, M_PI / 2), Eigen::Vector2d(0, 1));
	EXPECT_NEAR(zy[1], -M_PI / 2, 1e-14);
}

TEST(SensorPose, NonFiniteSensorPoseThrows)
{
	const double nan = std::numeric_limits<double>::quiet_NaN();
	const double inf = std::numeric_limits<double>::infinity();
	const Eigen::Vector3d x(1, 2, 0.3);
	const Eigen::Vector2d f(5, 6);
	for (const Eigen::Vector3d& bad :
	     {Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(0, inf, 0), Eigen::Vector3d(0, 0, nan)})
	{
		for (MeasurementModel m : kModels)
		{
			EXPECT_THROW(observeFromSensor(m, x, bad, f), std::invalid_argument) << bad.transpose();
			EXPECT_THROW(inverseObserveFromSensor(m, x, bad, f), std::invalid_argument);
		}
		EXPECT_THROW(sensorPoseInWorld(x, bad), std::invalid_argument);
	}
	try
	{
		sensorPoseInWorld(x, Eigen::Vector3d(0.3, nan, 0));
		FAIL() << "expected a throw";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
	}
	// A feature at the sensor (not at the robot's origin): range 0 is a domain error.
	EXPECT_THROW(rangeBearingObserveFromSensor(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.3, 0, 0),
	                                           Eigen::Vector2d(0.3, 0)),
	             std::domain_error);
}
