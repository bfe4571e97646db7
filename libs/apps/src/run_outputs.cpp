#include <dynslam/apps/run_outputs.h>
#include <dynslam/landmark_ids.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dynslam::apps
{
void makeOutputDir(const std::string& dir)
{
	namespace fs = std::filesystem;
	std::error_code ec;
	if (fs::is_directory(dir, ec)) return;
	fs::create_directories(dir, ec);
	if (!ec && fs::is_directory(dir)) return;
	// Name the part of the path that is in the way, if any.
	std::string why = ec ? ec.message() : "unknown reason";
	for (fs::path p = fs::path(dir); !p.empty(); p = p.parent_path())
	{
		std::error_code e2;
		if (fs::exists(p, e2) && !fs::is_directory(p, e2))
		{
			why = "'" + p.string() + "' is a file, not a folder";
			break;
		}
		if (p == p.parent_path()) break;
	}
	if (!why.empty()) why[0] = char(std::tolower(static_cast<unsigned char>(why[0])));
	throw std::runtime_error("cannot create the output folder '" + dir + "': " + why +
	                         " (give another folder with -o/--out)");
}

std::string timeBaseWarning(const TFilterRun& run, const TGroundTruth& gt)
{
	for (const auto& e : run.est.ego)
	{
		if (e.step < 0 || size_t(e.step) >= gt.t.size() || !std::isfinite(e.t)) continue;
		const double g = gt.t[size_t(e.step)];
		if (std::abs(e.t - g) > 1e-3)
		{
			std::ostringstream os;
			os.precision(15);
			os << "the ground truth's time stamps differ from the rawlog's (step " << e.step << ": "
			   << g << " s vs " << e.t
			   << " s): trajectory.tum has the rawlog's; evo will not associate it with the "
			      "ground truth's TUM file (regenerate the ground truth or shift its t column)";
			return os.str();
		}
	}
	return {};
}

TGroundTruth estimatesAsReference(const TFilterRun& run)
{
	TGroundTruth g;
	int maxStep = -1;
	for (const auto& e : run.est.ego) maxStep = std::max(maxStep, e.step);
	const size_t n = size_t(maxStep + 1);
	g.t.assign(n, std::numeric_limits<double>::quiet_NaN());
	g.ego.assign(n, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
	for (const auto& e : run.est.ego)
	{
		g.t[size_t(e.step)] = e.t;
		g.ego[size_t(e.step)] = e.mean;
	}
	for (const auto& l : run.est.landmarks)
		if (ids::isStatic(l.id)) g.landmarks[l.id] = l.mean;
	return g;
}
}  // namespace dynslam::apps
