#include <dynslam/common/config_utils.h>
#include <dynslam/kitti/CKittiOptions.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>

namespace dynslam::kitti
{
namespace
{
void loadDetectionKeys(const mrpt::config::CConfigFileBase& c, const std::string& sec,
                       TDetectionOptions& d)
{
	using namespace dynslam::config;
	if (has(c, sec, "detection_classes"))
	{
		const std::string v = c.read_string(sec, "detection_classes", "");
		d.classes.clear();
		std::istringstream in(v);
		for (std::string w; in >> w;)
		{
			if (w != "Car" && w != "Pedestrian" && w != "Cyclist")
				fail(sec, "detection_classes", v, "'" + w + "' is not Car, Pedestrian or Cyclist");
			if (std::find(d.classes.begin(), d.classes.end(), w) != d.classes.end())
				fail(sec, "detection_classes", v, "'" + w + "' given twice");
			d.classes.push_back(w);
		}
		if (d.classes.empty()) fail(sec, "detection_classes", v, "no class");
	}
	if (has(c, sec, "detection_min_score"))
	{
		const std::string v = c.read_string(sec, "detection_min_score", "");
		d.min_score = v == "none" ? -std::numeric_limits<double>::infinity()
		                          : readDouble(c, sec, "detection_min_score", 0.0);
		if (!std::isfinite(d.min_score) && v != "none")
			fail(sec, "detection_min_score", v, "a finite number, or none");
	}
}
}  // namespace

void TKittiOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                       const std::string& sec)
{
	using namespace dynslam::config;
	rejectUnknownKeys(c, sec,
	                  {"dt", "max_range", "fov_deg", "static_radius", "noise", "odometry_noise",
	                   "seed", "std_range", "std_bearing", "odo_std_xy", "odo_std_xy_per_m",
	                   "odo_std_phi", "odo_std_phi_per_m", "detection_groups", "detection_classes",
	                   "detection_min_score", "pose_scale"});
	auto& o = import;
	o.dt = readPositive(c, sec, "dt", o.dt);
	o.max_range = readPositive(c, sec, "max_range", o.max_range);
	o.fov_deg = readPositive(c, sec, "fov_deg", o.fov_deg);
	if (o.fov_deg > 360) fail(sec, "fov_deg", c.read_string(sec, "fov_deg", ""), "must be <= 360");
	o.static_radius = readNonNegative(c, sec, "static_radius", o.static_radius);
	const std::vector<std::string> modes{"gaussian", "none"};
	o.noise =
	    readChoice(c, sec, "noise", modes, int(o.noise)) == 0 ? ENoise::Gaussian : ENoise::None;
	o.odometry_noise = readChoice(c, sec, "odometry_noise", modes, int(o.odometry_noise)) == 0
	                       ? ENoise::Gaussian
	                       : ENoise::None;
	const long seed = readInt(c, sec, "seed", long(o.seed));
	if (seed < 0 || seed > 4294967295L)
		fail(sec, "seed", std::to_string(seed), "must be in 0..2^32-1");
	o.seed = uint32_t(seed);
	o.std_range = readPositive(c, sec, "std_range", o.std_range);
	o.std_bearing = readPositive(c, sec, "std_bearing", o.std_bearing);
	o.odo_std_xy = readPositive(c, sec, "odo_std_xy", o.odo_std_xy);
	o.odo_std_xy_per_m = readNonNegative(c, sec, "odo_std_xy_per_m", o.odo_std_xy_per_m);
	o.odo_std_phi = readPositive(c, sec, "odo_std_phi", o.odo_std_phi);
	o.odo_std_phi_per_m = readNonNegative(c, sec, "odo_std_phi_per_m", o.odo_std_phi_per_m);
	o.detection_groups = readBool(c, sec, "detection_groups", o.detection_groups);
	loadDetectionKeys(c, sec, detections);
	if (has(c, sec, "pose_scale"))
	{
		const std::string v = c.read_string(sec, "pose_scale", "");
		o.pose_scale_auto = v == "auto";
		if (!o.pose_scale_auto) o.pose_scale = readPositive(c, sec, "pose_scale", 1.0);
		if (!o.pose_scale_auto && !std::isfinite(o.pose_scale))
			fail(sec, "pose_scale", v, "auto, or a finite number > 0");
	}
}

void TKittiOptions::dumpToTextStream(std::ostream& out) const
{
	const auto& o = import;
	const auto mode = [](ENoise n) { return n == ENoise::Gaussian ? "gaussian" : "none"; };
	out.precision(17);
	out << "[KITTI_Import]\n"
	    << "dt = " << o.dt << "\n"
	    << "max_range = " << o.max_range << "\n"
	    << "fov_deg = " << o.fov_deg << "\n"
	    << "static_radius = " << o.static_radius << "\n"
	    << "noise = " << mode(o.noise) << "\n"
	    << "odometry_noise = " << mode(o.odometry_noise) << "\n"
	    << "seed = " << o.seed << "\n"
	    << "std_range = " << o.std_range << "\n"
	    << "std_bearing = " << o.std_bearing << "\n"
	    << "odo_std_xy = " << o.odo_std_xy << "\n"
	    << "odo_std_xy_per_m = " << o.odo_std_xy_per_m << "\n"
	    << "odo_std_phi = " << o.odo_std_phi << "\n"
	    << "odo_std_phi_per_m = " << o.odo_std_phi_per_m << "\n"
	    << "detection_groups = " << (o.detection_groups ? "true" : "false") << "\n"
	    << "pose_scale = ";
	if (o.pose_scale_auto)
		out << "auto";
	else
		out << o.pose_scale;
	out << "\ndetection_classes =";
	for (const auto& cls : detections.classes) out << " " << cls;
	out << "\ndetection_min_score = ";
	if (std::isfinite(detections.min_score))
		out << detections.min_score << "\n";
	else
		out << "none\n";
}

void TKittiSimOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                          const std::string& sec)
{
	using namespace dynslam::config;
	rejectUnknownKeys(c, sec,
	                  {"seed", "miss_probability", "false_positives_per_frame", "fp_min_range",
	                   "fp_max_range", "fp_fov_deg", "fp_score_min", "fp_score_max", "score_min",
	                   "score_max", "std_xy", "std_yaw", "std_size", "flip_probability"});
	auto& o = sim;
	const long seed = readInt(c, sec, "seed", long(o.seed));
	if (seed < 0 || seed > 4294967295L)
		fail(sec, "seed", std::to_string(seed), "must be in 0..2^32-1");
	o.seed = uint32_t(seed);
	o.miss_probability = readNonNegative(c, sec, "miss_probability", o.miss_probability);
	o.false_positives_per_frame =
	    readNonNegative(c, sec, "false_positives_per_frame", o.false_positives_per_frame);
	o.fp_min_range = readNonNegative(c, sec, "fp_min_range", o.fp_min_range);
	o.fp_max_range = readNonNegative(c, sec, "fp_max_range", o.fp_max_range);
	o.fp_fov_deg = readPositive(c, sec, "fp_fov_deg", o.fp_fov_deg);
	o.fp_score_min = readDouble(c, sec, "fp_score_min", o.fp_score_min);
	o.fp_score_max = readDouble(c, sec, "fp_score_max", o.fp_score_max);
	o.score_min = readDouble(c, sec, "score_min", o.score_min);
	o.score_max = readDouble(c, sec, "score_max", o.score_max);
	o.std_xy = readNonNegative(c, sec, "std_xy", o.std_xy);
	o.std_yaw = readNonNegative(c, sec, "std_yaw", o.std_yaw);
	o.std_size = readNonNegative(c, sec, "std_size", o.std_size);
	o.flip_probability = readNonNegative(c, sec, "flip_probability", o.flip_probability);
	try
	{
		checkDetectionSimOptions(o);
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument("[" + sec + "] " + e.what());
	}
}

void TKittiSimOptions::dumpToTextStream(std::ostream& out) const
{
	const auto& o = sim;
	out.precision(17);
	out << "[KITTI_SimulateDetections]\nseed = " << o.seed
	    << "\nmiss_probability = " << o.miss_probability
	    << "\nfalse_positives_per_frame = " << o.false_positives_per_frame
	    << "\nfp_min_range = " << o.fp_min_range << "\nfp_max_range = " << o.fp_max_range
	    << "\nfp_fov_deg = " << o.fp_fov_deg << "\nfp_score_min = " << o.fp_score_min
	    << "\nfp_score_max = " << o.fp_score_max << "\nscore_min = " << o.score_min
	    << "\nscore_max = " << o.score_max << "\nstd_xy = " << o.std_xy
	    << "\nstd_yaw = " << o.std_yaw << "\nstd_size = " << o.std_size
	    << "\nflip_probability = " << o.flip_probability << "\n";
}
}  // namespace dynslam::kitti
