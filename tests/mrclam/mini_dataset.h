#pragma once
/** A tiny synthetic MRCLAM folder written into a temp dir, for the bad-input tests.
 * Subjects 1..20 have barcode 10 + subject; robots drive straight lines during 10 s;
 * robot 1 (the ego) measures landmark 6 and robot 2 at t = 1, 1.01, 2 and 3 s. */
#include <dynslam_test/temp_dir.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace mrclam_test
{
inline const char* kHeader =
    "# UTIAS Multi-Robot Cooperative Localization and Mapping Dataset\n"
    "# synthetic test file\n"
    "# format line\n"
    "# columns\n";

inline std::string tempDir(const std::string& name)
{
	return dynslam_test::tempDir("mrclam_" + name);  // removed when the test program ends
}

inline void writeFile(const std::string& path, const std::string& body)
{
	std::ofstream f(path, std::ios::binary);
	f << body;
}

/** Body rows of Robot1_Measurement.dat of the mini data set. */
inline std::string miniMeasurements()
{
	return "1.000 16 2.0 0.5\n"   // landmark 6
	       "1.010 12 1.5 -0.2\n"  // robot 2, same step (10 ms later)
	       "2.000 16 2.1 0.4\n"
	       "3.000 12 1.4 -0.1\n";
}

inline std::string writeMiniDataset(const std::string& name)
{
	const std::string d = tempDir(name);
	std::string bc = kHeader, lm = kHeader;
	for (int s = 1; s <= 20; s++) bc += std::to_string(s) + "\t" + std::to_string(10 + s) + "\n";
	for (int s = 6; s <= 20; s++)
		lm += std::to_string(s) + " " + std::to_string(s * 0.5) + " 1.0 0.0001 0.0001\n";
	writeFile(d + "/Barcodes.dat", bc);
	writeFile(d + "/Landmark_Groundtruth.dat", lm);
	for (int r = 1; r <= 5; r++)
	{
		std::string gt = kHeader;
		for (int i = 0; i <= 100; i++)
		{
			const double t = 0.1 * i;
			gt += std::to_string(t) + " " + std::to_string(0.1 * t) + " " + std::to_string(r) +
			      " 0.0\n";
		}
		writeFile(d + "/Robot" + std::to_string(r) + "_Groundtruth.dat", gt);
	}
	std::string odo = kHeader;
	for (int i = 0; i <= 100; i++) odo += std::to_string(0.1 * i) + " 0.1 0.0\n";
	writeFile(d + "/Robot1_Odometry.dat", odo);
	writeFile(d + "/Robot1_Measurement.dat", std::string(kHeader) + miniMeasurements());
	return d;
}
}  // namespace mrclam_test
