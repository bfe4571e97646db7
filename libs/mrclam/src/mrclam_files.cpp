#include <dynslam/io/text_fields.h>
#include <dynslam/mrclam/mrclam_files.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::mrclam
{
TTable readTable(const std::string& path, size_t ncols, const std::vector<size_t>& integerCols,
                 int timeCol)
{
	std::ifstream f(path, std::ios::binary);
	if (!f) throw std::runtime_error(path + ": cannot open file (missing?)");
	TTable t;
	std::string s;
	int line = 0;
	while (std::getline(f, s))
	{
		++line;
		if (!s.empty() && s.back() == '\r') s.pop_back();
		const auto first = s.find_first_not_of(" \t");
		if (first == std::string::npos || s[first] == '#') continue;
		const auto toks = io::splitWhitespace(s);
		if (toks.size() != ncols)
			io::throwAtLine(path, line,
			                "expected " + std::to_string(ncols) + " columns, found " +
			                    std::to_string(toks.size()) + " ('" + s + "')");
		std::vector<double> row(ncols);
		for (size_t c = 0; c < ncols; c++)
		{
			row[c] = io::parseFiniteField(toks[c], path, line, c);
			for (size_t ic : integerCols)
				if (ic == c && row[c] != std::floor(row[c]))
					io::throwAtLine(path, line,
					                "column " + std::to_string(c + 1) + ": '" + toks[c] +
					                    "' is not an integer");
		}
		if (timeCol >= 0 && !t.rows.empty() && row[timeCol] < t.rows.back()[timeCol])
		{
			std::ostringstream m;
			m.precision(15);
			m << "timestamps out of order: " << row[timeCol] << " after " << t.rows.back()[timeCol]
			  << " (line " << t.lines.back() << ")";
			io::throwAtLine(path, line, m.str());
		}
		t.rows.push_back(std::move(row));
		t.lines.push_back(line);
	}
	if (f.bad()) throw std::runtime_error(path + ": read error");
	return t;
}

std::map<int, int> readBarcodes(const std::string& path)
{
	const auto t = readTable(path, 2, {0, 1});
	std::map<int, int> out;
	std::map<int, int> subjects;
	for (size_t i = 0; i < t.rows.size(); i++)
	{
		const int subject = static_cast<int>(t.rows[i][0]);
		const int barcode = static_cast<int>(t.rows[i][1]);
		if (!isRobotSubject(subject) && !isLandmarkSubject(subject))
			io::throwAtLine(path, t.lines[i],
			                "subject " + std::to_string(subject) +
			                    " outside 1..20 (robots 1-5, landmarks 6-20)");
		if (!out.emplace(barcode, subject).second)
			io::throwAtLine(path, t.lines[i], "duplicate barcode " + std::to_string(barcode));
		if (!subjects.emplace(subject, barcode).second)
			io::throwAtLine(path, t.lines[i], "duplicate subject " + std::to_string(subject));
	}
	if (out.empty()) throw std::runtime_error(path + ": no barcodes");
	return out;
}

std::map<int, Eigen::Vector2d> readLandmarks(const std::string& path)
{
	const auto t = readTable(path, 5, {0});
	std::map<int, Eigen::Vector2d> out;
	for (size_t i = 0; i < t.rows.size(); i++)
	{
		const int subject = static_cast<int>(t.rows[i][0]);
		if (!isLandmarkSubject(subject))
			io::throwAtLine(path, t.lines[i],
			                "subject " + std::to_string(subject) + " is not a landmark (6..20)");
		if (!out.emplace(subject, Eigen::Vector2d(t.rows[i][1], t.rows[i][2])).second)
			io::throwAtLine(path, t.lines[i], "duplicate subject " + std::to_string(subject));
	}
	if (out.empty()) throw std::runtime_error(path + ": no landmarks");
	return out;
}

std::vector<TOdometryRow> readOdometry(const std::string& path)
{
	const auto t = readTable(path, 3, {}, 0);
	std::vector<TOdometryRow> out;
	out.reserve(t.rows.size());
	for (const auto& r : t.rows) out.push_back({r[0], r[1], r[2]});
	if (out.empty()) throw std::runtime_error(path + ": no odometry rows");
	return out;
}

std::vector<TMeasurementRow> readMeasurements(const std::string& path)
{
	const auto t = readTable(path, 4, {1}, 0);
	std::vector<TMeasurementRow> out;
	out.reserve(t.rows.size());
	for (size_t i = 0; i < t.rows.size(); i++)
	{
		const auto& r = t.rows[i];
		if (r[2] < 0) io::throwAtLine(path, t.lines[i], "negative range " + std::to_string(r[2]));
		out.push_back({r[0], static_cast<int>(r[1]), r[2], r[3], t.lines[i]});
	}
	if (out.empty()) throw std::runtime_error(path + ": no measurements");
	return out;
}

std::vector<TPoseRow> readGroundTruthPoses(const std::string& path)
{
	const auto t = readTable(path, 4, {}, 0);
	std::vector<TPoseRow> out;
	out.reserve(t.rows.size());
	for (const auto& r : t.rows) out.push_back({r[0], r[1], r[2], r[3]});
	if (out.size() < 2) throw std::runtime_error(path + ": fewer than 2 ground-truth rows");
	return out;
}

std::string robotFile(const std::string& dir, int robot, const std::string& kind)
{
	return dir + "/Robot" + std::to_string(robot) + "_" + kind + ".dat";
}

TDataset loadDataset(const std::string& dir, int egoRobot)
{
	if (!isRobotSubject(egoRobot))
		throw std::invalid_argument("ego robot " + std::to_string(egoRobot) + " outside " +
		                            std::to_string(kFirstRobot) + ".." +
		                            std::to_string(kLastRobot));
	TDataset d;
	d.dir = dir;
	d.ego = egoRobot;
	d.barcodeToSubject = readBarcodes(dir + "/Barcodes.dat");
	d.landmarks = readLandmarks(dir + "/Landmark_Groundtruth.dat");
	d.odometry = readOdometry(robotFile(dir, egoRobot, "Odometry"));
	d.measurements = readMeasurements(robotFile(dir, egoRobot, "Measurement"));
	for (int r = kFirstRobot; r <= kLastRobot; r++)
		d.groundTruth[r] = readGroundTruthPoses(robotFile(dir, r, "Groundtruth"));
	return d;
}
}  // namespace dynslam::mrclam
