#include <dynslam/config_utils.h>
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
}  // namespace dynslam::kitti
