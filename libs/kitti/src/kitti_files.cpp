#include <dynslam/io/text_fields.h>
#include <dynslam/kitti/kitti_files.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <utility>

namespace dynslam::kitti
{
namespace
{
int integer(const std::string& tok, const std::string& path, int line, size_t col)
{
	const double v = io::parseFiniteField(tok, path, line, col);
	if (v != std::floor(v) || std::abs(v) > 1e9)
		io::throwAtLine(path, line,
		                "column " + std::to_string(col + 1) + ": '" + tok + "' is not an integer");
	return int(v);
}

std::ifstream openIn(const std::string& path)
{
	if (!std::filesystem::is_regular_file(path))
		throw std::runtime_error(path + ": file not found");
	std::ifstream f(path, std::ios::binary);
	if (!f) throw std::runtime_error(path + ": cannot open file");
	return f;
}

const std::vector<std::string> kTypes = {
    "Car",     "Van",  "Truck", "Pedestrian", "Person", "Person_sitting",
    "Cyclist", "Tram", "Misc",  "DontCare"};
}  // namespace

bool isKnownType(const std::string& type)
{
	return std::find(kTypes.begin(), kTypes.end(), type) != kTypes.end();
}

void checkSequenceName(const std::string& seq)
{
	if (seq.size() != 4 ||
	    !std::all_of(seq.begin(), seq.end(), [](char c) { return c >= '0' && c <= '9'; }))
		throw std::invalid_argument("sequence '" + seq + "': expected four digits, e.g. 0000");
}

std::string sequenceFile(const std::string& dir, const std::string& seq)
{
	return (std::filesystem::path(dir) / (seq + ".txt")).string();
}

std::vector<TCameraPose> readPoses(const std::string& path)
{
	auto f = openIn(path);
	std::vector<TCameraPose> poses;
	std::string s;
	int line = 0;
	while (std::getline(f, s))
	{
		++line;
		if (!s.empty() && s.back() == '\r') s.pop_back();
		const auto toks = io::splitWhitespace(s);
		if (toks.empty())
		{
			// a trailing empty line is fine; an empty line inside the file would shift frames
			std::string rest;
			while (std::getline(f, rest))
				if (!io::splitWhitespace(rest).empty())
					io::throwAtLine(path, line, "empty line inside the pose file");
			break;
		}
		if (toks.size() != 12)
			io::throwAtLine(
			    path, line,
			    "expected 12 numbers (3x4 [R t]), found " + std::to_string(toks.size()));
		TCameraPose T;
		for (size_t i = 0; i < 12; ++i)
			T(long(i / 4), long(i % 4)) = io::parseFiniteField(toks[i], path, line, i);
		const Eigen::Matrix3d R = T.leftCols<3>();
		const double orth = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
		if (orth > 1e-3 || R.determinant() < 0)
			io::throwAtLine(
			    path, line,
			    "the 3x3 block is not a rotation (|R^T R - I| = " + std::to_string(orth) + ")");
		poses.push_back(T);
	}
	if (poses.empty()) throw std::runtime_error(path + ": no poses");
	return poses;
}

TKittiLabels readLabels(const std::string& path)
{
	auto f = openIn(path);
	TKittiLabels L;
	L.file = path;
	std::set<std::pair<int, int>> seen;
	std::string s;
	int line = 0;
	while (std::getline(f, s))
	{
		++line;
		if (!s.empty() && s.back() == '\r') s.pop_back();
		const auto t = io::splitWhitespace(s);
		if (t.empty()) continue;
		++L.rows;
		if (t.size() != 17)
			io::throwAtLine(path, line, "expected 17 columns, found " + std::to_string(t.size()));
		const int frame = integer(t[0], path, line, 0);
		const int track = integer(t[1], path, line, 1);
		if (frame < 0) io::throwAtLine(path, line, "negative frame " + t[0]);
		if (!isKnownType(t[2])) ++L.unknown_types[t[2]];
		std::vector<double> v(17);
		for (size_t i = 3; i < 17; ++i) v[i] = io::parseFiniteField(t[i], path, line, i);
		if (frame > L.max_frame)
		{
			L.max_frame = frame;
			L.max_frame_line = line;
		}
		if (t[2] == "DontCare")
		{
			++L.dontcare;
			continue;
		}
		++L.types[t[2]];
		if (track < 0) io::throwAtLine(path, line, "track_id " + t[1] + " on a " + t[2] + " box");
		if (!seen.emplace(frame, track).second)
			io::throwAtLine(path, line, "track " + t[1] + " given twice in frame " + t[0]);
		TKittiBox b;
		b.frame = frame;
		b.track = track;
		b.type = t[2];
		b.h = v[10];
		b.w = v[11];
		b.l = v[12];
		b.x = v[13];
		b.y = v[14];
		b.z = v[15];
		b.ry = v[16];
		b.line = line;
		if (!(b.w > 0 && b.l > 0 && b.h > 0) || b.z <= -999)
		{
			++L.no3d;
			continue;
		}
		L.boxes.push_back(b);
	}
	return L;
}

void checkLabelsAgainstPoses(const TKittiLabels& labels, size_t numPoses,
                             const std::string& posesPath)
{
	if (labels.max_frame >= 0 && size_t(labels.max_frame) >= numPoses)
		io::throwAtLine(labels.file, labels.max_frame_line,
		                "frame " + std::to_string(labels.max_frame) + " has no pose: " + posesPath +
		                    " has " + std::to_string(numPoses) + " lines (frames 0.." +
		                    std::to_string(numPoses - 1) + ")");
}
}  // namespace dynslam::kitti
