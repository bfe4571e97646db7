#include <dynslam/common/detection_boxes.h>
#include <dynslam/common/detection_groups.h>
#include <dynslam/common/odometry_action.h>
#include <dynslam/common/rawlog_file_writer.h>
#include <dynslam/kitti/rawlog_writer.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

namespace dynslam::kitti
{
namespace fs = std::filesystem;
namespace
{
mrpt::obs::CActionCollection makeAction(const TStep& s)
{
	mrpt::obs::CActionCollection acts;
	acts.insert(
	    makeOdometryMovement(Eigen::Vector3d(s.increment.x(), s.increment.y(), s.increment.z()),
	                         s.cov, mrpt::Clock::fromDouble(s.t)));
	return acts;
}

mrpt::obs::CObservationBearingRange::TMeasurement measurement(double range, double bearing,
                                                              int32_t id)
{
	mrpt::obs::CObservationBearingRange::TMeasurement z;
	z.range = float(range);
	z.yaw = float(bearing);
	z.pitch = 0;
	z.landmarkID = id;
	z.covariance.setZero();
	return z;
}

/** Detection mode: every box's corners (ID -1) and the DETECTION_GROUPS / DETECTION_BOXES
 * comments (dynslam/common/detection_boxes.h). */
void addBoxes(const TStep& s, mrpt::obs::CObservationBearingRange& obs,
              mrpt::obs::CSensoryFrame& sf)
{
	std::vector<int32_t> ids, groups;
	for (const auto& b : s.boxes)
		for (const auto& c : boxCorners(b))
		{
			obs.sensedData.push_back(measurement(c.norm(), std::atan2(c.y(), c.x()), -1));
			ids.push_back(-1);
			groups.push_back(b.group);
		}
	// the step's time stamp (a comment's default is "now"; MRPT's tools report it)
	auto g = makeDetectionGroups(ids, groups);
	auto c = makeDetectionBoxes(s.boxes);
	g->timestamp = c->timestamp = obs.timestamp;
	sf.insert(g);
	sf.insert(c);
}

mrpt::obs::CSensoryFrame makeFrame(const TStep& s, const TImportOptions& o, bool detections)
{
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	obs->sensorLabel = "RB";
	obs->timestamp = mrpt::Clock::fromDouble(s.t);
	obs->minSensorDistance = 0;
	obs->maxSensorDistance = float(o.max_range);
	obs->fieldOfView_yaw = float(o.fov_deg * M_PI / 180.0);
	obs->fieldOfView_pitch = 0;
	obs->sensorLocationOnRobot = mrpt::poses::CPose3D();
	obs->validCovariances = false;
	obs->sensor_std_range = float(o.std_range);
	obs->sensor_std_yaw = float(o.std_bearing);
	obs->sensor_std_pitch = 0;
	for (const auto& r : s.readings)
		obs->sensedData.push_back(measurement(r.range, r.bearing, r.id));
	mrpt::obs::CSensoryFrame sf;
	sf.insert(obs);
	if (detections)
		addBoxes(s, *obs, sf);
	else if (o.detection_groups)
	{
		// The hint of every corner: its box, the KITTI track ID (detection_groups.h).
		std::vector<int32_t> ids, groups;
		for (const auto& r : s.readings)
		{
			ids.push_back(r.id);
			groups.push_back(r.track);
		}
		auto g = makeDetectionGroups(ids, groups);
		g->timestamp = obs->timestamp;
		sf.insert(g);
	}
	return sf;
}

void writeText(const std::string& path, const std::function<void(std::ostream&)>& w)
{
	std::ofstream f(path);
	if (!f) throw std::runtime_error(path + ": cannot open for writing");
	f.precision(12);
	w(f);
	f.flush();
	if (!f) throw std::runtime_error(path + ": write error");
}

size_t boxesWritten(const TImportResult& res)
{
	size_t n = 0;
	for (const auto& s : res.steps) n += s.boxes.size();
	return n;
}

void writeExtras(const TImportResult& res, const TKittiOptions& opts, const std::string& dir,
                 const std::string& base)
{
	const auto file = [&](const std::string& s) { return (fs::path(dir) / (base + s)).string(); };
	const auto& tracks = res.tracks;
	writeText(file("_gt_tracks.csv"),
	          [&](std::ostream& f)
	          {
		          f << "step,t,track,type,moving,read,x,y,yaw\n";
		          for (const auto& r : res.track_steps)
			          f << r.step << ',' << res.gt.t[size_t(r.step)] << ',' << r.track << ','
			            << tracks.at(r.track).type << ',' << int(r.moving) << ',' << int(r.read)
			            << ',' << r.pose.x() << ',' << r.pose.y() << ',' << r.pose.z() << '\n';
	          });
	writeText(file("_gt_track_list.csv"),
	          [&](std::ostream& f)
	          {
		          f << "track,type,moving,radius,first_frame,last_frame,frames,read_frames,first_"
		               "read,object,length,width\n";
		          for (const auto& [id, t] : tracks)
			          f << t.track << ',' << t.type << ',' << int(t.moving) << ',' << t.radius
			            << ',' << t.first_frame << ',' << t.last_frame << ',' << t.frames << ','
			            << t.read_frames << ',' << t.first_read << ',' << t.object << ','
			            << t.length << ',' << t.width << '\n';
	          });
	writeText(file("_gt_ids.csv"),
	          [&](std::ostream& f)
	          {
		          f << "id,track,corner,moving,object\n";
		          for (const auto& r : res.ids)
			          f << r.id << ',' << r.track << ',' << r.corner << ',' << int(r.moving) << ','
			            << tracks.at(r.track).object << '\n';
	          });
	writeText(file("_gt_boxes.csv"),
	          [&](std::ostream& f)
	          {
		          f.precision(17);
		          f << "step,t,track,type,moving,read,x,y,yaw,length,width\n";
		          for (const auto& r : res.track_steps)
			          f << r.step << ',' << res.gt.t[size_t(r.step)] << ',' << r.track << ','
			            << tracks.at(r.track).type << ',' << int(r.moving) << ',' << int(r.read)
			            << ',' << r.pose.x() << ',' << r.pose.y() << ',' << r.pose.z() << ','
			            << r.length << ',' << r.width << '\n';
	          });
	// the class of every rawlog reading: the annotated corners' (detection mode: no truth per
	// reading, the detections are not matched to tracks; not written)
	if (!res.detections) io::writeClassGroundTruth(readingClasses(res), file("_gt_classes.csv"));
	writeText(file("_summary.txt"), [&](std::ostream& f) { f << res.summary.toText(); });
	writeText(file("_scenario.ini"),
	          [&](std::ostream& f)
	          {
		          const auto& s = res.summary;
		          f << "; Written by dynslam-kitti: the import's effective options (the noise\n"
		            << "; used) and counts. World frame = the ego frame of frame 0, so the\n"
		            << "; filters start at the origin with zero covariance.\n"
		            << "[KITTI_ImportResult]\nsequence = " << s.sequence << "\nmode = "
		            << (res.detections          ? "detections"
		                : opts.import.anonymous ? "anonymous"
		                                        : "labelled")
		            << "\nsteps = " << s.steps
		            << "\nreadings = " << (res.detections ? 4 * boxesWritten(res) : s.readings)
		            << "\ndetection_boxes = " << boxesWritten(res)
		            << "\nstatic_tracks = " << s.static_tracks
		            << "\nmoving_tracks = " << s.moving_tracks
		            << "\npath_length = " << s.path_length << "\nfloor_n = " << s.floor_n
		            << "\nfloor_trans_rmse = " << s.floor_trans_rmse
		            << "\nfloor_rot_rmse = " << s.floor_rot_rmse
		            << "\nstatic_corner_rms = " << s.static_corner_rms
		            << "\ntrajectory_scale = " << s.trajectory_scale
		            << "\npose_scale_applied = " << s.pose_scale
		            << "\ntrajectory_scale_unscaled = " << s.trajectory_scale_unscaled
		            << "\n\n[DynamicKFSLAM]\ninitial_pose = [0 0 0]\nSigma_0 = [0 0 0]\n\n";
		          opts.dumpToTextStream(f);
	          });
}
}  // namespace

void writeRawlog(const TImportResult& res, const TImportOptions& opts, const std::string& path)
{
	CRawlogFileWriter out(path, "writeRawlog");
	for (const auto& s : res.steps)
		out.writeStep(makeAction(s), makeFrame(s, opts, res.detections));
	out.close();
}

std::vector<std::string> writeImport(const TImportResult& res, const TKittiOptions& opts,
                                     const std::string& dir, const std::string& base)
{
	fs::create_directories(dir);
	const fs::path tmp = fs::path(dir) / ("." + base + ".tmp-" + std::to_string(::getpid()));
	std::vector<std::string> written;
	try
	{
		fs::remove_all(tmp);
		fs::create_directories(tmp);
		writeRawlog(res, opts.import, (tmp / (base + ".rawlog")).string());
		io::writeGroundTruth(res.gt, tmp.string(), base);
		writeExtras(res, opts, tmp.string(), base);
		// refuse before moving anything if a destination cannot be replaced by a file
		for (const auto& e : fs::directory_iterator(tmp))
			if (fs::is_directory(fs::path(dir) / e.path().filename()))
				throw std::runtime_error((fs::path(dir) / e.path().filename()).string() +
				                         ": is a folder, cannot write the file there");
		for (const auto& e : fs::directory_iterator(tmp))
		{
			const fs::path dst = fs::path(dir) / e.path().filename();
			fs::rename(e.path(), dst);
			written.push_back(dst.string());
		}
		fs::remove(tmp);
	}
	catch (...)
	{
		std::error_code ec;
		fs::remove_all(tmp, ec);
		throw;
	}
	std::sort(written.begin(), written.end());
	return written;
}
}  // namespace dynslam::kitti
