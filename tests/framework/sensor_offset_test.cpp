/** A sensor that is not at the robot's origin (sensorLocationOnRobot), end to end through every
 * back-end (the EKF, Alg. 1 and every windowed configuration): the same simulated highway with
 * the sensor at the origin and at s = (0.3 m, -0.1 m, 0.2 rad) gives errors of the same order;
 * the same offset data with the sensor pose stripped (the model without the offset) does not. */
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <iostream>

#include "any_backend.h"
#include "backends_ini.h"

using namespace dynslam;

namespace
{
const char* const kIni = dynslam_test::kBackendsIni;

struct TRun
{
	std::vector<mrpt::obs::CActionCollection::Ptr> actions;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	io::TGroundTruth gt;
};

TRun simulate(const Eigen::Vector3d& sensor, int steps)
{
	sim::TScenarioOptions so = sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/highway.ini");
	so.steps = steps;
	so.sensor_pose = sensor;
	TRun r;
	r.gt = sim::buildGroundTruth(so);
	auto m = sim::simulateMeasurements(r.gt, so, 7);
	r.actions = m.actions;
	r.frames = m.frames;
	return r;
}

/** The same frames with sensorLocationOnRobot set to the identity (deep copies). */
std::vector<mrpt::obs::CSensoryFrame::Ptr> stripSensorPose(
    const std::vector<mrpt::obs::CSensoryFrame::Ptr>& frames)
{
	std::vector<mrpt::obs::CSensoryFrame::Ptr> out;
	for (const auto& f : frames)
	{
		auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
		    *f->getObservationByClass<mrpt::obs::CObservationBearingRange>());
		obs->sensorLocationOnRobot = mrpt::poses::CPose3D();
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		out.push_back(sf);
	}
	return out;
}

struct TErrors
{
	double ate = 0, map = 0, pose = 0;
	size_t poses = 0;
};

/** ATE (RMSE of the ego position over the steps, no alignment: the run starts at the truth),
 * the worst static landmark error and the worst object translation error. */
TErrors errors(const std::string& kind, const TRun& r,
               const std::vector<mrpt::obs::CSensoryFrame::Ptr>& frames)
{
	auto be = dynslam_test::anyBackend(kind, kIni);
	double se = 0;
	for (size_t k = 0; k < r.actions.size(); ++k)
	{
		be->processActionObservation(r.actions[k], frames[k]);
		const auto p = be->getEgoPose();
		se += std::pow(p.mean.x() - r.gt.ego[k][0], 2) + std::pow(p.mean.y() - r.gt.ego[k][1], 2);
	}
	TErrors e;
	e.ate = std::sqrt(se / double(r.actions.size()));
	for (const auto& l : allStaticLandmarks(*be))
		e.map = std::max(e.map, (l.mean - r.gt.landmarks.at(l.id)).norm());
	for (const auto& [obj, tr] : be->getObjectTracks())
		for (const auto& p : tr.poses)
		{
			const Eigen::Vector3d& t = r.gt.objects.at(size_t(obj)).pose.at(size_t(p.step));
			e.pose = std::max(e.pose, (p.mean.head<2>() - t.head<2>()).norm());
			++e.poses;
		}
	return e;
}
}  // namespace

TEST(SensorOffset, EveryBackendSameErrorsWithAndWithoutTheOffset)
{
	const TRun origin = simulate(Eigen::Vector3d::Zero(), 20);
	const TRun offset = simulate(Eigen::Vector3d(0.3, -0.1, 0.2), 20);
	const auto stripped = stripSensorPose(offset.frames);
	for (const auto& kind : dynslam_test::allBackendKinds())
	{
		const TErrors a = errors(kind, origin, origin.frames);
		const TErrors b = errors(kind, offset, offset.frames);
		const TErrors x = errors(kind, offset, stripped);
		std::cout << "[sensor offset] " << kind << ": ATE " << a.ate << " m at the origin, "
		          << b.ate << " m with the offset, " << x.ate
		          << " m with the offset ignored; worst landmark " << a.map << ", " << b.map << ", "
		          << x.map << " m; worst object translation " << a.pose << ", " << b.pose << ", "
		          << x.pose << " m (" << a.poses << ", " << b.poses << " poses)\n";
		// Same order (3x either way): the offset changes the geometry of the noise draws, not
		// the accuracy.
		EXPECT_LT(b.ate, 3 * a.ate) << kind;
		EXPECT_LT(a.ate, 3 * b.ate) << kind;
		EXPECT_LT(b.map, 3 * a.map) << kind;
		EXPECT_LT(b.pose, 3 * a.pose) << kind;
		EXPECT_LT(a.pose, 3 * b.pose) << kind;
		EXPECT_EQ(a.poses, b.poses) << kind;
		EXPECT_GT(b.poses, 0u) << kind;
		// The offset matters: ignoring it is far worse.
		EXPECT_GT(x.ate, 100 * b.ate) << kind;
	}
}
