#pragma once
/** A tiny synthetic KITTI sequence for the importer tests, written into a temp folder:
 * 12 frames, the camera drives 1 m per frame along its z axis (ego x); a parked car (track 0)
 * 10 m ahead, 3 m to the left; a car (track 1) driving at 2 m per frame beside the ego, 4 m to
 * the right; a DontCare line per frame; a pedestrian (track 2) far outside the field of view
 * (fixed in the camera frame, so it moves in the world). The parked car leaves the 90 deg field
 * of view at frame 8 (bearing 56 deg) and is not annotated after it.
 */
#include <dynslam_test/temp_dir.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace kitti_test
{
inline std::string tempDir(const std::string& name)
{
	// Removed when the test program ends (dynslam_test/temp_dir.h).
	const std::filesystem::path d = dynslam_test::tempDir("kitti_test_" + name);
	std::filesystem::create_directories(d / "label_02");
	std::filesystem::create_directories(d / "poses");
	return d.string();
}

/** Camera pose line of frame k: identity rotation, t = (0, 0, k). */
inline std::string poseLine(int k) { return "1 0 0 0 0 1 0 0 0 0 1 " + std::to_string(double(k)); }

/** A label line; x, z camera frame (x right, z forward), ry yaw. */
inline std::string labelLine(int frame, int track, const std::string& type, double x, double z,
                             double ry, double l = 4.0, double w = 1.8)
{
	std::ostringstream o;
	o.precision(17);
	o << frame << ' ' << track << ' ' << type << " 0 0 -1.5 100 150 300 250 1.5 " << w << ' ' << l
	  << ' ' << x << " 1.6 " << z << ' ' << ry;
	return o.str();
}

inline std::vector<std::string> miniLabels(int frames = 12)
{
	std::vector<std::string> v;
	for (int k = 0; k < frames; ++k)
	{
		v.push_back(std::to_string(k) +
		            " -1 DontCare -1 -1 -10 1 2 3 4 -1000 -1000 -1000 -10 -1 -1 -1");
		// parked: world (10, 3) -> camera x = -3, z = 10 - k; length along the road (ry = -pi/2)
		if (10 - k > 1) v.push_back(labelLine(k, 0, "Car", -3, 10.0 - k, -M_PI / 2));
		// driving beside: world (5 + 2k, -4) -> camera x = 4, z = 5 + k
		v.push_back(labelLine(k, 1, "Car", 4, 5.0 + k, -M_PI / 2));
		// far to the side (bearing ~ -80 deg): outside the 90 deg field of view
		v.push_back(labelLine(k, 2, "Pedestrian", 20, 3.0, 0, 0.8, 0.6));
	}
	return v;
}

inline void writeLines(const std::string& path, const std::vector<std::string>& lines)
{
	std::ofstream f(path);
	for (const auto& l : lines) f << l << "\n";
}

/** Writes DIR/label_02/0007.txt and DIR/poses/0007.txt; returns DIR. */
inline std::string writeMiniSequence(const std::string& name, int poseFrames = 12,
                                     const std::vector<std::string>& labels = miniLabels())
{
	const std::string d = tempDir(name);
	std::vector<std::string> poses;
	for (int k = 0; k < poseFrames; ++k) poses.push_back(poseLine(k));
	writeLines(d + "/poses/0007.txt", poses);
	writeLines(d + "/label_02/0007.txt", labels);
	return d;
}
}  // namespace kitti_test
