#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/detection_simulator.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>

namespace dynslam::kitti
{
namespace
{
int classCode(const std::string& type)
{
	if (type == "Pedestrian") return 1;
	if (type == "Car") return 2;
	if (type == "Cyclist") return 3;
	return 0;
}

/** A detection in the camera frame; alpha from x, z and rot_y. */
TKittiDetection makeDetection(int frame, const std::string& type, double score, double h, double w,
                              double l, double x, double y, double z, double ry)
{
	TKittiDetection d;
	d.frame = frame;
	d.type = type;
	d.score = score;
	d.h = h, d.w = w, d.l = l, d.x = x, d.y = y, d.z = z;
	d.ry = ry;
	d.alpha = models::wrapToPi(ry - std::atan2(x, z));
	return d;
}

struct TSimulator
{
	const TDetectionSimOptions& o;
	std::mt19937 rng;
	std::uniform_real_distribution<double> U01{0.0, 1.0};
	std::normal_distribution<double> N01{0.0, 1.0};

	double uniform(double a, double b) { return a + (b - a) * U01(rng); }

	/** A label box as the detector sees it; false: missed. */
	bool detect(const TKittiBox& b, TKittiDetection& d)
	{
		if (U01(rng) < o.miss_probability) return false;
		const double x = b.x + o.std_xy * N01(rng), z = b.z + o.std_xy * N01(rng);
		double ry = b.ry + o.std_yaw * N01(rng);
		const double l = std::max(0.1, b.l + o.std_size * N01(rng));
		const double w = std::max(0.1, b.w + o.std_size * N01(rng));
		const double h = std::max(0.1, b.h + o.std_size * N01(rng));
		if (U01(rng) < o.flip_probability) ry += M_PI;
		if (o.std_yaw > 0 || o.flip_probability > 0) ry = models::wrapToPi(ry);
		d = makeDetection(b.frame, b.type, uniform(o.score_min, o.score_max), h, w, l, x, b.y, z,
		                  ry);
		return true;
	}

	TKittiDetection falsePositive(int frame)
	{
		const double r = uniform(o.fp_min_range, o.fp_max_range);
		const double half = o.fp_fov_deg * M_PI / 360.0;
		const double bearing = uniform(-half, half);
		// ego (forward, left) = (z, -x): camera x = -left, z = forward
		const double fwd = r * std::cos(bearing), left = r * std::sin(bearing);
		const double ry = uniform(-M_PI, M_PI);
		return makeDetection(frame, "Car", uniform(o.fp_score_min, o.fp_score_max), 1.5, 1.6, 3.9,
		                     -left, 1.65, fwd, ry);
	}
};
}  // namespace

void checkDetectionSimOptions(const TDetectionSimOptions& o)
{
	auto need = [](bool ok, const std::string& what)
	{
		if (!ok) throw std::invalid_argument("detection simulator options: " + what);
	};
	need(o.miss_probability >= 0 && o.miss_probability <= 1, "miss_probability in [0, 1]");
	need(o.flip_probability >= 0 && o.flip_probability <= 1, "flip_probability in [0, 1]");
	need(o.false_positives_per_frame >= 0 && std::isfinite(o.false_positives_per_frame),
	     "false_positives_per_frame >= 0");
	need(o.fp_min_range >= 0 && o.fp_min_range <= o.fp_max_range && std::isfinite(o.fp_max_range),
	     "0 <= fp_min_range <= fp_max_range");
	need(o.fp_fov_deg > 0 && o.fp_fov_deg <= 360, "fp_fov_deg in (0, 360]");
	need(std::isfinite(o.fp_score_min) && std::isfinite(o.fp_score_max) &&
	         o.fp_score_min <= o.fp_score_max,
	     "fp_score_min <= fp_score_max, finite");
	need(std::isfinite(o.score_min) && std::isfinite(o.score_max) && o.score_min <= o.score_max,
	     "score_min <= score_max, finite");
	for (const double s : {o.std_xy, o.std_yaw, o.std_size})
		need(s >= 0 && std::isfinite(s), "std_xy, std_yaw, std_size >= 0");
}

std::vector<TKittiDetection> simulateDetections(const TKittiLabels& labels, size_t numFrames,
                                                const TDetectionSimOptions& o)
{
	checkDetectionSimOptions(o);
	std::vector<std::vector<const TKittiBox*>> byFrame(numFrames);
	for (const auto& b : labels.boxes)
	{
		if (b.frame < 0 || size_t(b.frame) >= numFrames)
			throw std::invalid_argument(labels.file + ":" + std::to_string(b.line) + ": frame " +
			                            std::to_string(b.frame) + " beyond the " +
			                            std::to_string(numFrames) + " frames simulated");
		if (classCode(b.type) != 0) byFrame[size_t(b.frame)].push_back(&b);
	}
	TSimulator sim{o, std::mt19937(o.seed)};
	// (a Poisson mean must be > 0: drawn only when it is)
	std::poisson_distribution<int> fps(o.false_positives_per_frame > 0 ? o.false_positives_per_frame
	                                                                   : 1.0);
	std::vector<TKittiDetection> out;
	std::map<std::string, int> lines;
	for (size_t k = 0; k < numFrames; ++k)
	{
		TKittiDetection d;
		for (const TKittiBox* b : byFrame[k])
			if (sim.detect(*b, d)) out.push_back(d);
		const int n = o.false_positives_per_frame > 0 ? fps(sim.rng) : 0;
		for (int i = 0; i < n; ++i) out.push_back(sim.falsePositive(int(k)));
	}
	for (auto& d : out) d.line = ++lines[d.type];
	return out;
}

std::string detectionLine(const TKittiDetection& d)
{
	const int code = classCode(d.type);
	if (code == 0) throw std::invalid_argument("detection class '" + d.type + "'");
	std::ostringstream s;
	s.precision(17);
	s << d.frame << ',' << code << ',' << d.x1 << ',' << d.y1 << ',' << d.x2 << ',' << d.y2 << ','
	  << d.score << ',' << d.h << ',' << d.w << ',' << d.l << ',' << d.x << ',' << d.y << ',' << d.z
	  << ',' << d.ry << ',' << d.alpha;
	return s.str();
}

void writeDetectionFiles(const std::vector<TKittiDetection>& dets, const std::string& dir,
                         const std::string& sequence)
{
	checkSequenceName(sequence);
	std::map<std::string, std::ostringstream> text;
	for (const char* c : {"Pedestrian", "Car", "Cyclist"}) text[c];
	for (const auto& d : dets) text[d.type] << detectionLine(d) << '\n';  // checks the class
	for (auto& [cls, t] : text)
	{
		const std::filesystem::path folder = std::filesystem::path(dir) / cls;
		std::filesystem::create_directories(folder);
		const std::string path = sequenceFile(folder.string(), sequence);
		std::ofstream f(path);
		f << t.str();
		f.flush();
		if (!f) throw std::runtime_error(path + ": cannot write");
	}
}

void writeNominalCalib(const std::string& dir, const std::string& sequence)
{
	checkSequenceName(sequence);
	std::filesystem::create_directories(dir);
	const std::string path = sequenceFile(dir, sequence);
	std::ofstream f(path);
	f << "P0: 720 0 620 0 0 720 190 0 0 0 1 0\n"
	  << "P1: 720 0 620 -390 0 720 190 0 0 0 1 0\n"
	  << "P2: 720 0 620 45 0 720 190 0 0 0 1 0\n"
	  << "P3: 720 0 620 -340 0 720 190 0 0 0 1 0\n"
	  << "R_rect: 1 0 0 0 1 0 0 0 1\n"
	  << "Tr_velo_cam: 0 -1 0 0 0 0 -1 0 1 0 0 0\n"
	  << "Tr_imu_velo: 1 0 0 0 0 1 0 0 0 0 1 0\n";
	f.flush();
	if (!f) throw std::runtime_error(path + ": cannot write");
}
}  // namespace dynslam::kitti
