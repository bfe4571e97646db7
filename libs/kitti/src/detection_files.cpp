#include <dynslam/io/text_fields.h>
#include <dynslam/kitti/detection_files.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::kitti
{
namespace
{
std::ifstream openFile(const std::string& path)
{
	if (!std::filesystem::is_regular_file(path))
		throw std::runtime_error(path + ": file not found");
	std::ifstream f(path, std::ios::binary);
	if (!f) throw std::runtime_error(path + ": cannot open file");
	return f;
}

std::string trim(const std::string& s)
{
	const auto b = s.find_first_not_of(" \t\r");
	if (b == std::string::npos) return "";
	return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> splitCommas(const std::string& s)
{
	std::vector<std::string> out;
	std::stringstream ss(s);
	std::string tok;
	while (std::getline(ss, tok, ',')) out.push_back(trim(tok));
	if (!s.empty() && s.back() == ',') out.emplace_back();
	return out;
}

int integerField(const std::string& tok, const std::string& path, int line, size_t col)
{
	const double v = io::parseFiniteField(tok, path, line, col);
	if (v != std::floor(v) || std::abs(v) > 1e9)
		io::throwAtLine(path, line,
		                "column " + std::to_string(col + 1) + ": '" + tok + "' is not an integer");
	return int(v);
}

TKittiDetection parseDetection(const std::vector<std::string>& t, const std::string& path, int line,
                               const std::string& type)
{
	for (size_t i = 0; i < t.size(); ++i)
		if (t[i].empty())
			io::throwAtLine(path, line, "column " + std::to_string(i + 1) + " is empty");
	TKittiDetection d;
	d.line = line;
	d.frame = integerField(t[0], path, line, 0);
	if (d.frame < 0) io::throwAtLine(path, line, "negative frame " + t[0]);
	const int code = integerField(t[1], path, line, 1);
	d.type = detectionClassName(code);
	if (d.type.empty())
		io::throwAtLine(path, line,
		                "class " + t[1] + ": expected 1 (Pedestrian), 2 (Car), 3 (Cyclist)");
	if (d.type != type)
		io::throwAtLine(path, line, "class " + t[1] + " (" + d.type + ") in the " + type + " file");
	double v[15];
	for (size_t i = 2; i < 15; ++i) v[i] = io::parseFiniteField(t[i], path, line, i);
	d.x1 = v[2], d.y1 = v[3], d.x2 = v[4], d.y2 = v[5], d.score = v[6];
	d.h = v[7], d.w = v[8], d.l = v[9], d.x = v[10], d.y = v[11], d.z = v[12];
	d.ry = v[13], d.alpha = v[14];
	if (!(d.h > 0 && d.w > 0 && d.l > 0))
		io::throwAtLine(path, line,
		                "box size h, w, l must be > 0 (" + t[7] + ", " + t[8] + ", " + t[9] + ")");
	return d;
}

/** Canonical calibration key of a spelling, "" if unknown. */
std::string calibKey(const std::string& k)
{
	static const std::map<std::string, std::string> keys = {{"P0", "P0"},
	                                                        {"P1", "P1"},
	                                                        {"P2", "P2"},
	                                                        {"P3", "P3"},
	                                                        {"R0_rect", "R0_rect"},
	                                                        {"R_rect", "R0_rect"},
	                                                        {"Tr_velo_to_cam", "Tr_velo_to_cam"},
	                                                        {"Tr_velo_cam", "Tr_velo_to_cam"},
	                                                        {"Tr_imu_to_velo", "Tr_imu_to_velo"},
	                                                        {"Tr_imu_velo", "Tr_imu_to_velo"}};
	const auto it = keys.find(k);
	return it == keys.end() ? "" : it->second;
}

void checkRotation(const Eigen::Matrix3d& R, const std::string& path, int line,
                   const std::string& key)
{
	const double orth = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
	if (!(orth <= 1e-3) || R.determinant() < 0)
		io::throwAtLine(
		    path, line,
		    key + ": the 3x3 block is not a rotation (|R^T R - I| = " + std::to_string(orth) + ")");
}
}  // namespace

std::string detectionClassName(int code)
{
	switch (code)
	{
		case 1:
			return "Pedestrian";
		case 2:
			return "Car";
		case 3:
			return "Cyclist";
		default:
			return "";
	}
}

TKittiDetectionFile readDetections(const std::string& path, const std::string& type)
{
	if (type != "Pedestrian" && type != "Car" && type != "Cyclist")
		throw std::invalid_argument("detection class '" + type +
		                            "': expected Pedestrian, Car or Cyclist");
	auto f = openFile(path);
	TKittiDetectionFile D;
	D.file = path;
	D.type = type;
	std::string s;
	int line = 0;
	while (std::getline(f, s))
	{
		++line;
		if (trim(s).empty()) continue;
		const auto t = splitCommas(s);
		if (t.size() != 15)
			io::throwAtLine(
			    path, line,
			    "expected 15 comma-separated columns, found " + std::to_string(t.size()));
		D.detections.push_back(parseDetection(t, path, line, type));
		if (D.detections.back().frame > D.max_frame)
		{
			D.max_frame = D.detections.back().frame;
			D.max_frame_line = line;
		}
	}
	return D;
}

void checkDetectionsAgainstFrames(const TKittiDetectionFile& d, size_t numFrames,
                                  const std::string& posesPath)
{
	if (d.max_frame >= 0 && size_t(d.max_frame) >= numFrames)
		io::throwAtLine(d.file, d.max_frame_line,
		                "frame " + std::to_string(d.max_frame) + " is beyond the sequence: " +
		                    posesPath + " has " + std::to_string(numFrames) + " frames (0.." +
		                    std::to_string(numFrames - 1) + ")");
}

TKittiCalib readCalib(const std::string& path)
{
	auto f = openFile(path);
	std::map<std::string, std::pair<std::vector<double>, int>> got;
	std::string s;
	int line = 0;
	while (std::getline(f, s))
	{
		++line;
		if (trim(s).empty()) continue;
		const auto colon = s.find(':');
		if (colon == std::string::npos) io::throwAtLine(path, line, "expected 'KEY: numbers'");
		const std::string spelled = trim(s.substr(0, colon)), key = calibKey(spelled);
		if (key.empty()) io::throwAtLine(path, line, "unknown calibration key '" + spelled + "'");
		if (got.count(key)) io::throwAtLine(path, line, key + " given twice");
		const auto toks = io::splitWhitespace(s.substr(colon + 1));
		const size_t n = key == "R0_rect" ? 9 : 12;
		if (toks.size() != n)
			io::throwAtLine(path, line,
			                key + ": expected " + std::to_string(n) + " numbers, found " +
			                    std::to_string(toks.size()));
		std::vector<double> v;
		for (size_t i = 0; i < n; ++i) v.push_back(io::parseFiniteField(toks[i], path, line, i));
		got[key] = {v, line};
	}
	for (const char* k : {"P0", "P1", "P2", "P3", "R0_rect", "Tr_velo_to_cam", "Tr_imu_to_velo"})
		if (!got.count(k)) throw std::runtime_error(path + ": no " + k + " line");
	auto m34 = [&](const std::string& k)
	{
		Eigen::Matrix<double, 3, 4> M;
		for (int i = 0; i < 12; ++i) M(i / 4, i % 4) = got[k].first[size_t(i)];
		return M;
	};
	TKittiCalib c;
	for (int i = 0; i < 4; ++i) c.P[size_t(i)] = m34("P" + std::to_string(i));
	for (int i = 0; i < 9; ++i) c.R0_rect(i / 3, i % 3) = got["R0_rect"].first[size_t(i)];
	c.Tr_velo_to_cam = m34("Tr_velo_to_cam");
	c.Tr_imu_to_velo = m34("Tr_imu_to_velo");
	checkRotation(c.R0_rect, path, got["R0_rect"].second, "R0_rect");
	checkRotation(c.Tr_velo_to_cam.leftCols<3>(), path, got["Tr_velo_to_cam"].second,
	              "Tr_velo_to_cam");
	checkRotation(c.Tr_imu_to_velo.leftCols<3>(), path, got["Tr_imu_to_velo"].second,
	              "Tr_imu_to_velo");
	return c;
}
}  // namespace dynslam::kitti
