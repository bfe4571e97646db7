/** Bad input for the MRCLAM importer: each case gives a std::runtime_error naming file and
 * line (or a documented drop with a count), never a crash; the app exits non-zero. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/mrclam/CMrclamApp.h>
#include <dynslam/mrclam/import.h>
#include <dynslam/mrclam/mrclam_files.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mini_dataset.h"

using namespace dynslam::mrclam;
using namespace mrclam_test;

namespace
{
/** Runs loadDataset + importRobot and returns the exception text ("" if none). */
std::string importError(const std::string& dir, TImportResult* out = nullptr)
{
	try
	{
		const auto d = loadDataset(dir, 1);
		auto r = importRobot(d, TImportOptions());
		if (out) *out = r;
		return "";
	}
	catch (const std::runtime_error& e)
	{
		return e.what();
	}
}

void expectContains(const std::string& s, const std::string& part)
{
	EXPECT_NE(s.find(part), std::string::npos) << "message: '" << s << "' lacks '" << part << "'";
}
}  // namespace

TEST(MrclamBadInput, ValidMiniDatasetImports)
{
	const auto dir = writeMiniDataset("valid");
	TImportResult r;
	ASSERT_EQ(importError(dir, &r), "");
	// 1.000 and 1.010 form one step (group_window 0.05 s): 3 steps, 4 measurements
	EXPECT_EQ(r.summary.steps, 3u);
	EXPECT_EQ(r.summary.kept, 4u);
	EXPECT_EQ(r.summary.per_subject.at(6), 2u);
	EXPECT_EQ(r.summary.per_subject.at(2), 2u);
	ASSERT_EQ(r.steps[0].meas.size(), 2u);
	EXPECT_EQ(r.steps[0].meas[0].id, 6);
	EXPECT_EQ(r.steps[0].meas[1].id, dynslam::ids::objectFeatureId(2, 0));
	EXPECT_DOUBLE_EQ(r.steps[0].t, 1.0);
	EXPECT_EQ(r.summary.spurious + r.summary.duplicates + r.summary.own_barcode, 0u);
}

TEST(MrclamBadInput, MissingFile)
{
	const auto dir = writeMiniDataset("missing");
	std::filesystem::remove(dir + "/Robot1_Odometry.dat");
	const auto e = importError(dir);
	expectContains(e, "Robot1_Odometry.dat");
	expectContains(e, "cannot open");
	// a missing ground truth of another robot is an error too
	const auto dir2 = writeMiniDataset("missing_gt");
	std::filesystem::remove(dir2 + "/Robot4_Groundtruth.dat");
	expectContains(importError(dir2), "Robot4_Groundtruth.dat");
}

TEST(MrclamBadInput, MalformedLines)
{
	const auto dir = writeMiniDataset("malformed");
	const std::string f = dir + "/Robot1_Measurement.dat";
	// line 6 (4 header lines, then the 2nd row) has a non-numeric range
	writeFile(f, std::string(kHeader) + "1.000 16 2.0 0.5\n1.010 12 abc -0.2\n");
	auto e = importError(dir);
	expectContains(e, "Robot1_Measurement.dat:6:");
	expectContains(e, "not a number");
	// wrong column count
	writeFile(f, std::string(kHeader) + "1.000 16 2.0 0.5\n2.0 16 2.0\n");
	e = importError(dir);
	expectContains(e, "Robot1_Measurement.dat:6:");
	expectContains(e, "expected 4 columns, found 3");
	// a barcode that is not an integer
	writeFile(f, std::string(kHeader) + "1.000 16.5 2.0 0.5\n");
	e = importError(dir);
	expectContains(e, "Robot1_Measurement.dat:5:");
	expectContains(e, "not an integer");
	// malformed Barcodes.dat
	writeFile(dir + "/Barcodes.dat", std::string(kHeader) + "1 11\n2 x\n");
	e = importError(dir);
	expectContains(e, "Barcodes.dat:6:");
}

TEST(MrclamBadInput, TimestampsOutOfOrder)
{
	const auto dir = writeMiniDataset("order");
	writeFile(dir + "/Robot1_Measurement.dat",
	          std::string(kHeader) + "1.000 16 2.0 0.5\n2.000 16 2.1 0.4\n1.500 12 1.4 -0.1\n");
	auto e = importError(dir);
	expectContains(e, "Robot1_Measurement.dat:7:");
	expectContains(e, "timestamps out of order");
	const auto dir2 = writeMiniDataset("order_gt");
	writeFile(dir2 + "/Robot3_Groundtruth.dat",
	          std::string(kHeader) + "0.0 0 0 0\n5.0 1 0 0\n4.0 1 0 0\n10.0 1 0 0\n");
	e = importError(dir2);
	expectContains(e, "Robot3_Groundtruth.dat:7:");
	expectContains(e, "timestamps out of order");
}

TEST(MrclamBadInput, NonFiniteValues)
{
	const auto dir = writeMiniDataset("nan");
	std::string odo = kHeader;
	odo += "0.0 0.1 0.0\n0.1 nan 0.0\n";
	writeFile(dir + "/Robot1_Odometry.dat", odo);
	auto e = importError(dir);
	expectContains(e, "Robot1_Odometry.dat:6:");
	expectContains(e, "non-finite");
	writeFile(dir + "/Robot1_Odometry.dat", std::string(kHeader) + "0.0 0.1 inf\n");
	e = importError(dir);
	expectContains(e, "Robot1_Odometry.dat:5:");
	expectContains(e, "non-finite");
}

TEST(MrclamBadInput, UnknownOwnAndDuplicateBarcodesAreDroppedAndCounted)
{
	const auto dir = writeMiniDataset("drops");
	writeFile(dir + "/Robot1_Measurement.dat", std::string(kHeader) +
	                                               "1.000 16 2.0 0.5\n"  // landmark 6: kept
	                                               "1.001 99 3.0 0.1\n"  // unknown barcode
	                                               "1.002 11 1.0 0.0\n"  // the ego's own barcode
	                                               "1.003 16 2.5 0.6\n"  // landmark 6 again: dup
	                                               "2.000 99 3.0 0.1\n"  // unknown: step w/o data
	                                               "3.000 12 1.4 -0.1\n");
	TImportResult r;
	ASSERT_EQ(importError(dir, &r), "");
	EXPECT_EQ(r.summary.rows, 6u);
	EXPECT_EQ(r.summary.spurious, 2u);
	EXPECT_EQ(r.summary.spurious_per_barcode.at(99), 2u);
	EXPECT_EQ(r.summary.own_barcode, 1u);
	EXPECT_EQ(r.summary.duplicates, 1u);
	EXPECT_EQ(r.summary.kept, 2u);
	ASSERT_EQ(r.steps.size(), 2u);  // the group at t = 2 has no valid measurement: no step
	ASSERT_EQ(r.steps[0].meas.size(), 1u);
	EXPECT_DOUBLE_EQ(r.steps[0].meas[0].range, 2.0);  // the first reading is kept
	EXPECT_NE(r.summary.toText().find("dropped spurious barcodes: 2 (barcode 99: 2)"),
	          std::string::npos);
}

TEST(MrclamBadInput, CrlfAndBlankLinesTolerated)
{
	const auto dir = writeMiniDataset("crlf");
	std::string m = kHeader, mCrlf;
	m += miniMeasurements();
	for (char c : m)
	{
		if (c == '\n') mCrlf += '\r';
		mCrlf += c;
	}
	writeFile(dir + "/Robot1_Measurement.dat", mCrlf + "\r\n\r\n");
	TImportResult r;
	ASSERT_EQ(importError(dir, &r), "");
	EXPECT_EQ(r.summary.kept, 4u);
	EXPECT_EQ(r.summary.steps, 3u);
}

TEST(MrclamBadInput, AppExitsNonZeroWithTheMessage)
{
	const auto dir = writeMiniDataset("app");
	writeFile(dir + "/Robot1_Measurement.dat",
	          std::string(kHeader) + "1.000 16 2.0 0.5\n0.5 16 2 0\n");
	const std::string app = std::string(DYNSLAM_BINARY_DIR) + "/apps/dynslam-mrclam/dynslam-mrclam";
	ASSERT_TRUE(std::filesystem::exists(app)) << app;
	const std::string err = dir + "/stderr.txt";
	const std::string cmd =
	    app + " --dataset " + dir + " --robot 1 --out " + dir + "/out 2> " + err + " > /dev/null";
	const int rc = std::system(cmd.c_str());
	EXPECT_NE(rc, 0);
	std::ifstream f(err);
	std::stringstream ss;
	ss << f.rdbuf();
	expectContains(ss.str(), "Robot1_Measurement.dat:6: timestamps out of order");
	// a missing folder and a bad option value fail too
	EXPECT_NE(
	    std::system((app + " --dataset " + dir + "/nope --robot 1 --out x 2>/dev/null").c_str()),
	    0);
	EXPECT_NE(std::system((app + " --dataset " + dir + " --robot 9 --out x 2>/dev/null").c_str()),
	          0);
	writeFile(dir + "/bad.ini", "[MRCLAM_Import]\ngroup_windw = 0.05\n");
	EXPECT_NE(std::system((app + " --dataset " + dir + " --robot 1 --out x --config " + dir +
	                       "/bad.ini 2>" + err)
	                          .c_str()),
	          0);
	std::ifstream f2(err);
	std::stringstream ss2;
	ss2 << f2.rdbuf();
	expectContains(ss2.str(), "config file '" + dir + "/bad.ini': [MRCLAM_Import] group_windw");
}

TEST(MrclamBadInput, OptionsRejectInvalidValues)
{
	// through the app class: a config with a negative std
	const auto dir = writeMiniDataset("opts");
	writeFile(dir + "/neg.ini", "[MRCLAM_Import]\nstd_range = -1\n");
	CMrclamApp app;
	const std::string cfg = dir + "/neg.ini";
	const char* argv[] = {"dynslam-mrclam", "--dataset", dir.c_str(), "--robot",  "1",
	                      "--out",          dir.c_str(), "--config",  cfg.c_str()};
	try
	{
		app.initialize(9, argv);
		FAIL() << "no exception";
	}
	catch (const std::invalid_argument& e)
	{
		expectContains(e.what(), "config file '" + cfg + "': [MRCLAM_Import] std_range = '-1'");
	}
}

TEST(MrclamBadInput, NoiseModelOptions)
{
	auto load = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory c(text);
		TMrclamOptions o;
		o.loadFromConfigFile(c, "MRCLAM_Import");
		return o;
	};
	auto expectError = [&](const std::string& text, const std::string& msg)
	{
		try
		{
			load("[MRCLAM_Import]\n" + text + "\n");
			FAIL() << "no exception for " << text;
		}
		catch (const std::invalid_argument& e)
		{
			expectContains(e.what(), msg);
		}
	};
	expectError("odo_noise_model = colored",
	            "[MRCLAM_Import] odo_noise_model = 'colored': must be white or inflated");
	expectError("odo_tau_xy = 0.5", "[MRCLAM_Import] odo_tau_xy = '0.5': must be >= 1");
	expectError("odo_tau_phi = -2", "[MRCLAM_Import] odo_tau_phi = '-2': must be >= 1");
	expectError("odo_tau_phi = nan", "[MRCLAM_Import] odo_tau_phi = 'nan'");
	const auto o = load("[MRCLAM_Import]\nodo_noise_model = inflated\nodo_tau_xy = 4\n");
	EXPECT_EQ(o.import.odometry_noise.model, TOdometryNoiseModel::Model::inflated);
	EXPECT_EQ(o.import.odometry_noise.tau_xy, 4.0);
	EXPECT_EQ(o.import.odometry_noise.tau_phi, 1.0);  // the built-in default
}

TEST(MrclamBadInput, LeaveOutNeedsAllRobots)
{
	const auto dir = writeMiniDataset("leaveout");
	for (const std::vector<std::string>& extra :
	     {std::vector<std::string>{"--robot", "1", "--leave-out", "2"},
	      std::vector<std::string>{"--all-robots", "--leave-out", "7"}})
	{
		std::vector<std::string> args = {"dynslam-mrclam", "--dataset", dir, "--estimate-noise"};
		args.insert(args.end(), extra.begin(), extra.end());
		std::vector<const char*> argv;
		for (const auto& a : args) argv.push_back(a.c_str());
		CMrclamApp app;
		try
		{
			app.initialize(static_cast<int>(argv.size()), argv.data());
			FAIL() << "no exception";
		}
		catch (const std::invalid_argument& e)
		{
			expectContains(e.what(), "--leave-out needs --all-robots and a robot 1..5");
		}
	}
}
