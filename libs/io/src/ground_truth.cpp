/** @file ground_truth.cpp
 * Plain-text ground-truth files (format documented in ground_truth.h and doc/simulator.md).
 * Numbers are written with up to 17 significant digits, so reading gives back the same doubles. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/io/ground_truth.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dynslam::io
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string num(double v)
{
	if (std::isnan(v)) return "nan";
	// The shortest of 15..17 significant digits that reads back to the same double.
	char buf[40];
	for (int p = 15; p <= 17; ++p)
	{
		std::snprintf(buf, sizeof(buf), "%.*g", p, v);
		if (std::strtod(buf, nullptr) == v) break;
	}
	return buf;
}

std::string fileName(const std::string& dir, const std::string& base, const char* suffix)
{
	return (std::filesystem::path(dir) / (base + suffix)).string();
}

std::ofstream openOut(const std::string& path)
{
	std::ofstream f(path, std::ios::binary);
	if (!f) throw std::runtime_error("writeGroundTruth: cannot write " + path);
	return f;
}

void closeOut(std::ofstream& f, const std::string& path)
{
	f.close();
	if (!f) throw std::runtime_error("writeGroundTruth: error writing " + path);
}

/** Line-by-line CSV reader with a fixed header and column count. */
class CCsvReader
{
public:
	CCsvReader(const std::string& path, const std::string& header)
	    : m_path(path), m_in(path, std::ios::binary)
	{
		if (!m_in) throw std::runtime_error("readGroundTruth: cannot open " + path);
		std::string h;
		if (!std::getline(m_in, h)) fail("empty file (missing header '" + header + "')");
		++m_line;
		if (!h.empty() && h.back() == '\r') h.pop_back();
		if (h != header) fail("header '" + h + "' differs from '" + header + "'");
		for (char c : header)
			if (c == ',') ++m_cols;
		++m_cols;
	}
	/** Reads the next non-empty row; false at the end of the file. */
	bool next(std::vector<double>& row)
	{
		std::string s;
		while (std::getline(m_in, s))
		{
			++m_line;
			if (!s.empty() && s.back() == '\r') s.pop_back();
			if (s.empty()) continue;
			row.clear();
			std::stringstream ss(s);
			std::string tok;
			while (std::getline(ss, tok, ','))
			{
				const char* b = tok.c_str();
				char* e = nullptr;
				errno = 0;
				const double v = std::strtod(b, &e);
				if (e == b || *e != '\0') fail("field '" + tok + "' is not a number");
				row.push_back(v);
			}
			if (s.back() == ',') fail("trailing comma");
			if (int(row.size()) != m_cols)
				fail(std::to_string(row.size()) + " fields, expected " + std::to_string(m_cols));
			return true;
		}
		return false;
	}
	/** Field i as an integer (must be integral and finite). */
	long integer(const std::vector<double>& row, int i, const char* what) const
	{
		const double v = row[i];
		if (!std::isfinite(v) || v != std::floor(v) || std::abs(v) > 2.1e9)
			fail(std::string(what) + " = " + num(v) + " is not an integer");
		return long(v);
	}
	[[noreturn]] void fail(const std::string& what) const
	{
		throw std::runtime_error("readGroundTruth: " + m_path + ":" + std::to_string(m_line) +
		                         ": " + what);
	}

private:
	std::string m_path;
	std::ifstream m_in;
	int m_line = 0;
	int m_cols = 0;
};
}  // namespace

void TGroundTruth::checkConsistent() const
{
	const size_t n = ego.size();
	if (t.size() != n)
		throw std::runtime_error("TGroundTruth: " + std::to_string(t.size()) + " times for " +
		                         std::to_string(n) + " ego poses");
	for (size_t i = 0; i < objects.size(); ++i)
	{
		const TObjectGroundTruth& o = objects[i];
		const std::string name = "TGroundTruth: object " + std::to_string(o.object);
		if (o.object != int32_t(i))
			throw std::runtime_error(name + " stored at index " + std::to_string(i));
		if (o.num_features < 1) throw std::runtime_error(name + " has no features");
		if (o.features.size() != n || o.pose.size() != n || o.visible.size() != n)
			throw std::runtime_error(name +
			                         ": per-step vectors differ in length from the ego path");
		for (const auto& f : o.features)
			if (f.cols() != o.num_features)
				throw std::runtime_error(name + ": feature matrix with wrong column count");
		if (o.first_step < -1 || o.first_step >= int(std::max<size_t>(n, 1)))
			throw std::runtime_error(name + ": first_step out of range");
	}
	for (const auto& [id, p] : landmarks)
		if (!ids::isStatic(id))
			throw std::runtime_error("TGroundTruth: landmark ID " + std::to_string(id) +
			                         " is not static");
}

void writeGroundTruth(const TGroundTruth& gt, const std::string& dir, const std::string& base)
{
	gt.checkConsistent();
	std::filesystem::create_directories(dir);
	const size_t n = gt.numSteps();
	{
		const std::string p = fileName(dir, base, "_gt_ego.csv");
		auto f = openOut(p);
		f << "step,t,x,y,theta\n";
		for (size_t k = 0; k < n; ++k)
			f << k << ',' << num(gt.t[k]) << ',' << num(gt.ego[k][0]) << ',' << num(gt.ego[k][1])
			  << ',' << num(gt.ego[k][2]) << '\n';
		closeOut(f, p);
	}
	{
		const std::string p = fileName(dir, base, "_gt_ego.tum");
		auto f = openOut(p);
		f << "# t x y z qx qy qz qw\n";
		for (size_t k = 0; k < n; ++k)
		{
			const double th = gt.ego[k][2];
			f << num(gt.t[k]) << ' ' << num(gt.ego[k][0]) << ' ' << num(gt.ego[k][1]) << " 0 0 0 "
			  << num(std::sin(th / 2)) << ' ' << num(std::cos(th / 2)) << '\n';
		}
		closeOut(f, p);
	}
	{
		const std::string p = fileName(dir, base, "_gt_landmarks.csv");
		auto f = openOut(p);
		f << "id,x,y\n";
		for (const auto& [id, pos] : gt.landmarks)
			f << id << ',' << num(pos[0]) << ',' << num(pos[1]) << '\n';
		closeOut(f, p);
	}
	{
		const std::string p = fileName(dir, base, "_gt_objects.csv");
		auto f = openOut(p);
		f << "step,t,object,visible,first_step,dx,dy,dtheta\n";
		for (size_t k = 0; k < n; ++k)
			for (const auto& o : gt.objects)
			{
				const Eigen::Vector3d& xi = o.pose[k];
				f << k << ',' << num(gt.t[k]) << ',' << o.object << ',' << int(o.visible[k]) << ','
				  << o.first_step << ',' << num(xi[0]) << ',' << num(xi[1]) << ',' << num(xi[2])
				  << '\n';
			}
		closeOut(f, p);
	}
	{
		const std::string p = fileName(dir, base, "_gt_object_features.csv");
		auto f = openOut(p);
		f << "step,t,object,feature,id,x,y,visible\n";
		for (size_t k = 0; k < n; ++k)
			for (const auto& o : gt.objects)
				for (int j = 0; j < o.num_features; ++j)
					f << k << ',' << num(gt.t[k]) << ',' << o.object << ',' << j << ','
					  << ids::objectFeatureId(o.object, j) << ',' << num(o.features[k](0, j)) << ','
					  << num(o.features[k](1, j)) << ',' << int(o.visible[k]) << '\n';
		closeOut(f, p);
	}
}

namespace
{
/** BASE_gt_ego.csv: the step times and ego poses (rows in step order). */
void readEgoFile(const std::string& dir, const std::string& base, TGroundTruth& gt)
{
	std::vector<double> r;
	CCsvReader in(fileName(dir, base, "_gt_ego.csv"), "step,t,x,y,theta");
	while (in.next(r))
	{
		if (in.integer(r, 0, "step") != long(gt.ego.size()))
			in.fail("step " + num(r[0]) + " out of sequence");
		gt.t.push_back(r[1]);
		gt.ego.emplace_back(r[2], r[3], r[4]);
	}
}

/** BASE_gt_landmarks.csv: static landmark positions (unique static IDs). */
void readLandmarkFile(const std::string& dir, const std::string& base, TGroundTruth& gt)
{
	std::vector<double> r;
	CCsvReader in(fileName(dir, base, "_gt_landmarks.csv"), "id,x,y");
	while (in.next(r))
	{
		const long id = in.integer(r, 0, "id");
		if (!ids::isStatic(int32_t(id)))
			in.fail("id " + std::to_string(id) + " is not a static landmark ID");
		if (!gt.landmarks.emplace(int32_t(id), Eigen::Vector2d(r[1], r[2])).second)
			in.fail("duplicate landmark id " + std::to_string(id));
	}
}

/** BASE_gt_objects.csv: objects in index order, one row per object and step. */
void readObjectFile(const std::string& dir, const std::string& base, TGroundTruth& gt)
{
	std::vector<double> r;
	const size_t n = gt.ego.size();
	CCsvReader in(fileName(dir, base, "_gt_objects.csv"),
	              "step,t,object,visible,first_step,dx,dy,dtheta");
	std::vector<std::vector<uint8_t>> seen;
	while (in.next(r))
	{
		const long k = in.integer(r, 0, "step"), obj = in.integer(r, 2, "object");
		if (k < 0 || size_t(k) >= n) in.fail("step " + std::to_string(k) + " not in the ego path");
		if (obj < 0 || obj > ids::kMaxObject) in.fail("bad object index " + std::to_string(obj));
		if (size_t(obj) >= gt.objects.size())
		{
			if (size_t(obj) != gt.objects.size())
				in.fail("object " + std::to_string(obj) + " out of order");
			TObjectGroundTruth o;
			o.object = int32_t(obj);
			o.first_step = int(in.integer(r, 4, "first_step"));
			o.pose.assign(n, Eigen::Vector3d::Constant(kNaN));
			o.visible.assign(n, 0);
			o.features.resize(n);
			gt.objects.push_back(std::move(o));
			seen.emplace_back(n, 0);
		}
		if (seen[obj][k]) in.fail("duplicate row for object " + std::to_string(obj));
		seen[obj][k] = 1;
		TObjectGroundTruth& o = gt.objects[obj];
		if (in.integer(r, 4, "first_step") != o.first_step) in.fail("first_step changes");
		const long vis = in.integer(r, 3, "visible");
		if (vis != 0 && vis != 1) in.fail("visible must be 0 or 1");
		o.visible[k] = uint8_t(vis);
		o.pose[k] = Eigen::Vector3d(r[5], r[6], r[7]);
	}
	for (size_t i = 0; i < seen.size(); ++i)
		for (size_t k = 0; k < n; ++k)
			if (!seen[i][k])
				in.fail("object " + std::to_string(i) + " has no row for step " +
				        std::to_string(k));
}

/** BASE_gt_object_features.csv: the same number of features per object at every step. */
void readObjectFeatureFile(const std::string& dir, const std::string& base, TGroundTruth& gt)
{
	std::vector<double> r;
	const size_t n = gt.ego.size();
	CCsvReader in(fileName(dir, base, "_gt_object_features.csv"),
	              "step,t,object,feature,id,x,y,visible");
	std::vector<std::vector<std::vector<Eigen::Vector2d>>> feats(gt.objects.size());
	for (auto& f : feats) f.resize(n);
	while (in.next(r))
	{
		const long k = in.integer(r, 0, "step"), obj = in.integer(r, 2, "object");
		const long j = in.integer(r, 3, "feature"), id = in.integer(r, 4, "id");
		if (k < 0 || size_t(k) >= n) in.fail("step " + std::to_string(k) + " not in the ego path");
		if (obj < 0 || size_t(obj) >= gt.objects.size())
			in.fail("object " + std::to_string(obj) + " missing from the objects file");
		if (j < 0 || j >= ids::kFeaturesPerObject)
			in.fail("bad feature index " + std::to_string(j));
		if (id != ids::objectFeatureId(int32_t(obj), int32_t(j)))
			in.fail("id " + std::to_string(id) + " does not match object/feature");
		auto& v = feats[obj][k];
		if (j != long(v.size())) in.fail("feature " + std::to_string(j) + " out of order");
		v.emplace_back(r[5], r[6]);
	}
	for (size_t i = 0; i < feats.size(); ++i)
	{
		TObjectGroundTruth& o = gt.objects[i];
		o.num_features = n ? int(feats[i][0].size()) : 0;
		for (size_t k = 0; k < n; ++k)
		{
			if (int(feats[i][k].size()) != o.num_features || o.num_features == 0)
				in.fail("object " + std::to_string(i) + " step " + std::to_string(k) +
				        " has an inconsistent number of features");
			o.features[k].resize(2, o.num_features);
			for (int j = 0; j < o.num_features; ++j) o.features[k].col(j) = feats[i][k][j];
		}
	}
}

}  // namespace

TGroundTruth readGroundTruth(const std::string& dir, const std::string& base)
{
	TGroundTruth gt;
	readEgoFile(dir, base, gt);
	readLandmarkFile(dir, base, gt);
	readObjectFile(dir, base, gt);
	readObjectFeatureFile(dir, base, gt);
	gt.checkConsistent();
	return gt;
}
}  // namespace dynslam::io
