/** @file box_ground_truth.cpp
 * The KITTI importer's box truth: strict reader (see box_ground_truth.h). */
#include <dynslam/io/box_ground_truth.h>
#include <dynslam/io/text_fields.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace dynslam::io
{
namespace
{
/** The comma-separated rows of a CSV with a header; columns found by name. */
struct TCsv
{
	std::string path;
	std::map<std::string, size_t> col;
	std::vector<std::vector<std::string>> rows;
	std::vector<int> lines;
	const std::string& at(size_t r, const std::string& name) const { return rows[r][col.at(name)]; }
	double num(size_t r, const std::string& name) const
	{
		return parseFiniteField(at(r, name), path, lines[r], col.at(name));
	}
};

std::vector<std::string> splitComma(const std::string& s)
{
	std::vector<std::string> out;
	std::stringstream ss(s);
	std::string tok;
	while (std::getline(ss, tok, ',')) out.push_back(tok);
	if (!s.empty() && s.back() == ',') out.emplace_back();
	return out;
}

TCsv readCsv(const std::string& path, const std::vector<std::string>& needed)
{
	std::ifstream f(path);
	if (!f) throw std::runtime_error(path + ": cannot open the file");
	TCsv c;
	c.path = path;
	std::string line;
	int n = 0;
	if (!std::getline(f, line)) throwAtLine(path, 1, "empty file (a header is expected)");
	++n;
	const auto header = splitComma(line);
	for (size_t i = 0; i < header.size(); ++i) c.col[header[i]] = i;
	for (const auto& k : needed)
		if (!c.col.count(k)) throwAtLine(path, 1, "the header has no column '" + k + "'");
	while (std::getline(f, line))
	{
		++n;
		if (line.empty()) continue;
		auto row = splitComma(line);
		if (row.size() != header.size())
			throwAtLine(path, n,
			            std::to_string(row.size()) + " columns, the header has " +
			                std::to_string(header.size()));
		c.rows.push_back(std::move(row));
		c.lines.push_back(n);
	}
	return c;
}
}  // namespace

bool hasBoxGroundTruth(const std::string& base)
{
	return std::filesystem::exists(base + "_gt_tracks.csv") &&
	       std::filesystem::exists(base + "_gt_track_list.csv");
}

std::vector<TTruthBox> readBoxGroundTruth(const std::string& base)
{
	const TCsv list = readCsv(base + "_gt_track_list.csv", {"track", "length", "width"});
	std::map<int32_t, Eigen::Vector2d> extent;
	for (size_t r = 0; r < list.rows.size(); ++r)
	{
		const double id = list.num(r, "track");
		const Eigen::Vector2d e(list.num(r, "length"), list.num(r, "width"));
		if (!(e.minCoeff() > 0))
			throwAtLine(list.path, list.lines[r], "length and width must be > 0");
		extent[int32_t(id)] = e;
	}
	const TCsv tracks =
	    readCsv(base + "_gt_tracks.csv", {"step", "track", "type", "x", "y", "yaw"});
	std::vector<TTruthBox> out;
	out.reserve(tracks.rows.size());
	for (size_t r = 0; r < tracks.rows.size(); ++r)
	{
		TTruthBox b;
		const double step = tracks.num(r, "step");
		if (step < 0 || step != std::floor(step))
			throwAtLine(tracks.path, tracks.lines[r], "step must be an integer >= 0");
		b.step = int(step);
		b.track = int32_t(tracks.num(r, "track"));
		b.type = tracks.at(r, "type");
		b.world = Eigen::Vector3d(tracks.num(r, "x"), tracks.num(r, "y"), tracks.num(r, "yaw"));
		const auto e = extent.find(b.track);
		if (e == extent.end())
			throwAtLine(tracks.path, tracks.lines[r],
			            "track " + std::to_string(b.track) + " is not in " + list.path);
		b.extent = e->second;
		out.push_back(std::move(b));
	}
	return out;
}
}  // namespace dynslam::io
