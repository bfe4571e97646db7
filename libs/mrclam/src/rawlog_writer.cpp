#include <dynslam/common/odometry_action.h>
#include <dynslam/common/rawlog_file_writer.h>
#include <dynslam/mrclam/anonymous.h>
#include <dynslam/mrclam/rawlog_writer.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/system/datetime.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::mrclam
{
namespace
{
mrpt::obs::CActionCollection makeAction(const TStep& s)
{
	mrpt::obs::CActionCollection acts;
	acts.insert(makeOdometryMovement(
	    Eigen::Vector3d(s.increment.delta.x(), s.increment.delta.y(), s.increment.delta.z()), s.cov,
	    mrpt::Clock::fromDouble(s.t)));
	return acts;
}

mrpt::obs::CSensoryFrame makeFrame(const TStep& s, const TImportOptions& o)
{
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	obs->sensorLabel = "RB";
	obs->timestamp = mrpt::Clock::fromDouble(s.t);
	obs->minSensorDistance = 0;
	obs->maxSensorDistance = static_cast<float>(o.max_range);
	obs->fieldOfView_yaw = static_cast<float>(2 * M_PI);
	obs->fieldOfView_pitch = 0;
	obs->sensorLocationOnRobot = mrpt::poses::CPose3D();
	obs->validCovariances = false;
	obs->sensor_std_range = static_cast<float>(o.std_range);
	obs->sensor_std_yaw = static_cast<float>(o.std_bearing);
	obs->sensor_std_pitch = 0;
	for (const auto& m : s.meas)
	{
		mrpt::obs::CObservationBearingRange::TMeasurement z;
		z.range = static_cast<float>(m.range);
		z.yaw = static_cast<float>(m.bearing);
		z.pitch = 0;
		z.landmarkID = m.id;
		z.covariance.setZero();
		obs->sensedData.push_back(z);
	}
	mrpt::obs::CSensoryFrame sf;
	sf.insert(obs);
	return sf;
}
}  // namespace

void writeRawlog(const TImportResult& res, const TImportOptions& opts, const std::string& path)
{
	CRawlogFileWriter out(path, "writeRawlog");
	for (const auto& s : res.steps) out.writeStep(makeAction(s), makeFrame(s, opts));
	out.close();
}

void writeImport(const TImportResult& res, const TMrclamOptions& opts, const std::string& dir,
                 const std::string& base)
{
	std::filesystem::create_directories(dir);
	const auto file = [&](const std::string& suffix)
	{ return (std::filesystem::path(dir) / (base + suffix)).string(); };
	writeRawlog(res, opts.import, file(".rawlog"));
	io::writeGroundTruth(res.gt, dir, base);
	io::writeClassGroundTruth(classGroundTruth(res), file("_gt_classes.csv"));
	{
		std::ofstream f(file("_summary.txt"));
		f << res.summary.toText();
		if (!f) throw std::runtime_error(file("_summary.txt") + ": write error");
	}
	std::ofstream f(file("_import.ini"));
	const auto& s = res.summary;
	f.precision(17);
	f << "; Written by dynslam-mrclam. World frame: the ego's ground-truth pose at step 0, so\n"
	  << "; the filter starts at the origin with zero covariance (exact by construction).\n"
	  << "; [DynamicKFSLAM] here holds only the start; the other filter keys (measurement\n"
	  << "; model, noise) are in config/mrclam.ini.\n"
	  << "[MRCLAM_ImportResult]\n"
	  << "dataset = " << s.dataset << "\n"
	  << "ego_robot = " << s.ego << "\n"
	  << "steps = " << s.steps << "\n"
	  << "t_first = " << s.t_first << "\n"
	  << "t_last = " << s.t_last << "\n"
	  << "origin_vicon = [" << s.origin.x() << " " << s.origin.y() << " " << s.origin.z() << "]\n"
	  << "ids = " << (s.anonymous_ids.empty() ? "labelled" : "anonymous") << "\n";
	if (!s.anonymous_ids.empty()) f << "anonymous_seed = " << s.anonymous_seed << "\n";
	f << "\n"
	  << "[DynamicKFSLAM]\n"
	  << "initial_pose = [0 0 0]\n"
	  << "Sigma_0 = [0 0 0]\n\n";
	opts.dumpToTextStream(f);
	if (!f) throw std::runtime_error(file("_import.ini") + ": write error");
}
}  // namespace dynslam::mrclam
