/** @file ground_truth_mrpt.cpp
 * Ground truth in MRPT's text formats (simul-landmarks, kf-slam); see ground_truth.h. */
#include <dynslam/io/ground_truth.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::io
{
namespace
{
struct TTextMatrix
{
	std::vector<std::vector<double>> rows;
	std::vector<int> lines;  ///< 1-based line number of each row
};

[[noreturn]] void failAt(const std::string& file, int line, const std::string& what)
{
	throw std::runtime_error("readMrptGroundTruth: " + file +
	                         (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what);
}

/** An MRPT text matrix (CMatrixDouble::saveToTextFile style) with exactly `cols` columns. */
TTextMatrix readTextMatrix(const std::string& file, size_t cols, const char* what)
{
	std::ifstream in(file);
	if (!in) failAt(file, 0, std::string("cannot open the ") + what + " file");
	TTextMatrix m;
	std::string line;
	for (int n = 1; std::getline(in, line); ++n)
	{
		const auto b = line.find_first_not_of(" \t\r");
		if (b == std::string::npos || line[b] == '%' || line[b] == '#') continue;
		std::istringstream ss(line);
		std::vector<double> row;
		for (std::string tok; ss >> tok;)
		{
			char* e = nullptr;
			const double v = std::strtod(tok.c_str(), &e);
			if (e == tok.c_str() || *e != '\0' || !std::isfinite(v))
				failAt(file, n, "'" + tok + "' is not a finite number");
			row.push_back(v);
		}
		if (row.size() != cols)
			failAt(file, n,
			       std::to_string(row.size()) + " columns, expected " + std::to_string(cols) +
			           " (" + what + ")");
		m.rows.push_back(std::move(row));
		m.lines.push_back(n);
	}
	return m;
}

bool zero(double v) { return std::abs(v) < 1e-9; }
}  // namespace

TGroundTruth readMrptGroundTruth(const std::string& pathFile, const std::string& landmarksFile,
                                 size_t rowsExpected, const std::vector<size_t>& rowOfStep,
                                 const std::vector<double>& stepTimes)
{
	if (rowOfStep.size() != stepTimes.size())
		throw std::invalid_argument("readMrptGroundTruth: rowOfStep and stepTimes differ in size");
	const TTextMatrix path = readTextMatrix(pathFile, 6, "robot path: x y z yaw pitch roll");
	if (path.rows.size() != rowsExpected)
		failAt(pathFile, 0,
		       std::to_string(path.rows.size()) + " poses, expected " +
		           std::to_string(rowsExpected) +
		           " (one per sensory frame of the rawlog, as simul-landmarks writes)");
	for (size_t i = 0; i < path.rows.size(); ++i)
	{
		const auto& r = path.rows[i];
		if (!zero(r[2]) || !zero(r[4]) || !zero(r[5]))
			failAt(pathFile, path.lines[i], "not a 2-D pose (z, pitch, roll must be 0)");
	}
	TGroundTruth gt;
	for (size_t k = 0; k < rowOfStep.size(); ++k)
	{
		if (rowOfStep[k] >= path.rows.size())
			failAt(pathFile, 0,
			       "step " + std::to_string(k) + " needs pose row " + std::to_string(rowOfStep[k]));
		const auto& r = path.rows[rowOfStep[k]];
		gt.t.push_back(stepTimes[k]);
		gt.ego.emplace_back(r[0], r[1], r[3]);
	}
	const TTextMatrix lms =
	    readTextMatrix(landmarksFile, 7, "landmarks: x y z type seenCount tLastSeen ID");
	for (size_t i = 0; i < lms.rows.size(); ++i)
	{
		const auto& r = lms.rows[i];
		if (!zero(r[2]))
			failAt(landmarksFile, lms.lines[i],
			       "landmark z = " + std::to_string(r[2]) +
			           " (2-D SLAM: set min_z = max_z = 0 in simul-landmarks' INI)");
		if (r[6] != std::floor(r[6]) || r[6] < 0 || r[6] > 99999)
			failAt(landmarksFile, lms.lines[i],
			       "landmark ID " + std::to_string(r[6]) +
			           " is not an integer in 0..99999 (the static-landmark ID range)");
		if (!gt.landmarks.emplace(int32_t(r[6]), Eigen::Vector2d(r[0], r[1])).second)
			failAt(landmarksFile, lms.lines[i],
			       "duplicate landmark ID " + std::to_string(int(r[6])));
	}
	gt.checkConsistent();
	return gt;
}
}  // namespace dynslam::io
