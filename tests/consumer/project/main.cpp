// Runs the dynamic EKF for a few steps through the installed package and prints the pose.
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/landmark_ids.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <iostream>

int main()
{
	dynslam::CDynamicKFSLAM2D f;
	f.options.measurement_model = dynslam::models::MeasurementModel::RangeBearing;
	f.options.Sigma_v = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();
	f.reset();
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
		f.processActionObservation(acts, sf);
	}
	const auto p = f.getEgoPose();
	std::cout << "consumer: x=" << p.mean.x() << " landmarks=" << f.getStaticLandmarks().size() << "\n";
	return (p.mean.x() > 4.0 && f.getStaticLandmarks().size() == 1) ? 0 : 1;
}
