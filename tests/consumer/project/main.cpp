// Uses every installed dynslam library through the package: the dynamic EKF (ekf), configured
// from an INI through the model options (common), the framework's Alg. 1 (framework) and MRPT's
// static filter behind the project's interface (apps) on the same few steps, and one function
// each of core, io, sim, eval and mrclam. Exit code 0 only if every result is as expected.
// With DYNSLAM_CONSUMER_WITHOUT_APPS (tests/consumer/project_estimator): everything but apps.
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#ifndef DYNSLAM_CONSUMER_WITHOUT_APPS
#include <dynslam/apps/CStaticBaselineBackend.h>
#endif
#include <dynslam/common/config_utils.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/eval/chi2.h>
#include <dynslam/framework/backend_factory.h>
#include <dynslam/io/number_format.h>
#include <dynslam/kitti/geometry.h>
#include <dynslam/mrclam/odometry.h>
#include <dynslam/sim/motion.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <iostream>

namespace
{
const char* kIni = R"(
[DynamicKFSLAM]
measurement_model = range_bearing
Sigma_v = [1e-4 1e-6]
Sigma_0 = [1e-6 1e-6 1e-8]
[RangeBearingKFSLAM]
std_sensor_range = 0.01
std_sensor_yaw_deg = 0.0573
)";

bool check(bool ok, const char* what)
{
	std::cout << "consumer: " << what << (ok ? " ok" : " FAILED") << "\n";
	return ok;
}

/** Five steps of 1 m along x, each seeing static landmark 3 at (10, 2). */
void drive(dynslam::ISlamBackend& b)
{
	for (int k = 0; k < 5; ++k)
	{
		mrpt::obs::CActionRobotMovement2D mov;
		mrpt::math::CMatrixDouble33 cov;
		cov.setDiagonal(1e-4);
		mov.poseChange = mrpt::poses::CPosePDFGaussian::Create(mrpt::poses::CPose2D(1, 0, 0), cov);
		auto acts = mrpt::obs::CActionCollection::Create();
		acts->insert(mov);
		auto obs = mrpt::obs::CObservationBearingRange::Create();
		mrpt::obs::CObservationBearingRange::TMeasurement m;
		m.landmarkID = 3;
		m.range = float(std::hypot(10.0 - (k + 1), 2.0));
		m.yaw = float(std::atan2(2.0, 10.0 - (k + 1)));
		m.pitch = 0;
		obs->sensedData.push_back(m);
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		b.processActionObservation(acts, sf);
	}
}
}  // namespace

int main()
{
	try
	{
		mrpt::config::CConfigFileMemory ini(kIni);
		bool ok = true;
		// common + ekf
		ok &= check(dynslam::config::readDouble(ini, "RangeBearingKFSLAM", "std_sensor_range", 0,
		                                        true) == 0.01,
		            "common: config::readDouble");
		dynslam::CDynamicKFSLAM2D ekf;
		ekf.loadOptions(ini);
		ok &=
		    check(ekf.options.measurement_model == dynslam::models::MeasurementModel::RangeBearing,
		          "common: TModelOptions from the INI");
		drive(ekf);
		const double x = ekf.getEgoPose().mean.x();
		std::cout << "consumer: ekf x=" << x << " landmarks=" << ekf.getStaticLandmarks().size()
		          << "\n";
		ok &= check(std::abs(x - 5.0) < 1e-3 && ekf.getStaticLandmarks().size() == 1,
		            "ekf: CDynamicKFSLAM2D");
		// framework: Alg. 1 equals the EKF on the same steps and model
		auto alg1 = dynslam::framework::makeBackend("alg1", ini, "Backend");
		drive(*alg1);
		ok &= check(std::abs(alg1->getEgoPose().mean.x() - x) < 1e-6, "framework: Alg. 1 = EKF");
#ifndef DYNSLAM_CONSUMER_WITHOUT_APPS
		// apps: MRPT's static EKF-SLAM through the project's wrapper. MRPT's filter skips the
		// prediction while its map is empty, so it misses the first 1 m: x = 4, not 5.
		dynslam::apps::CStaticBaselineBackend st(
		    dynslam::apps::CStaticBaselineBackend::Mode::StaticOnly);
		st.loadOptions(ini);
		drive(st);
		const double xs = st.getEgoPose().mean.x();
		std::cout << "consumer: static baseline x=" << xs
		          << " landmarks=" << st.getStaticLandmarks().size() << "\n";
		ok &= check(std::abs(xs - 4.0) < 1e-3 && st.getStaticLandmarks().size() == 1,
		            "apps: CStaticBaselineBackend");
#endif
		// core, io, sim, eval, mrclam
		ok &= check(dynslam::ids::isStatic(3) &&
		                dynslam::ids::isObjectFeature(dynslam::ids::objectFeatureId(1, 2)),
		            "core: landmark IDs");
		ok &= check(dynslam::sim::carCorners(4.0, 2.0).cols() == 4, "sim: carCorners");
		ok &= check(std::abs(dynslam::chi2Quantile(0.95, 2) - 5.9915) < 1e-3, "core: chi2Quantile");
		ok &= check(std::abs(dynslam::eval::averageChi2Bounds(2, 1).upper - 7.3778) < 1e-3,
		            "eval: averageChi2Bounds");
		ok &= check(dynslam::io::formatShortest(0.1) == "0.1", "io: formatShortest");
		ok &= check(
		    (dynslam::mrclam::unicycleArc(1.0, 0.0, 2.0) - Eigen::Vector3d(2, 0, 0)).norm() < 1e-12,
		    "mrclam: unicycleArc");
		// estimator, kitti
		dynslam::estimator::CIdRangeRouter router;
		const auto routed =
		    router.route(0, {{dynslam::ids::objectFeatureId(2, 0), Eigen::Vector2d(1, 0)}},
		                 [](int32_t) { return false; });
		ok &= check(routed.readings.size() == 1 &&
		                routed.readings[0].route == dynslam::estimator::Route::ObjectFirstSighting,
		            "estimator: CIdRangeRouter");
		ok &= check((dynslam::kitti::cameraToEgo(1.0, 5.0) - Eigen::Vector2d(5, -1)).norm() < 1e-12,
		            "kitti: cameraToEgo");
		return ok ? 0 : 1;
	}
	catch (const std::exception& e)
	{
		std::cerr << "consumer: " << e.what() << "\n";
		return 1;
	}
}
