#include <dynslam/apps/run_outputs.h>
#include <dynslam/core/landmark_ids.h>
#include <unistd.h>

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

namespace
{
/** makeOutputDir's reason why `dir` cannot be a folder, or empty if it can (creating nothing). */
std::string whyNotUsable(const std::string& dir)
{
	namespace fs = std::filesystem;
	std::error_code ec;
	fs::path p = fs::absolute(fs::path(dir), ec);
	if (ec) return ec.message();
	for (; !p.empty(); p = p.parent_path())
	{
		std::error_code e2;
		if (fs::exists(p, e2))
		{
			if (!fs::is_directory(p, e2)) return "'" + p.string() + "' is a file, not a folder";
			if (::access(p.c_str(), W_OK | X_OK) != 0)
				return "folder '" + p.string() + "' is not writable";
			return {};
		}
		if (p == p.parent_path()) break;
	}
	return "no existing folder on the path";
}
}  // namespace

void checkOutputDirUsable(const std::string& dir)
{
	if (const std::string why = whyNotUsable(dir); !why.empty())
		throw std::runtime_error("cannot create the output folder '" + dir + "': " + why +
		                         " (give another folder with -o/--out)");
}

const std::vector<std::string>& videoExtensions()
{
	static const std::vector<std::string> e{".mp4", ".avi", ".mov", ".mkv"};
	return e;
}

void checkOutputFile(const std::string& path, const std::string& flag,
                     const std::vector<std::string>& extensions)
{
	namespace fs = std::filesystem;
	if (path.empty()) return;
	const std::string what = flag + " '" + path + "'";
	std::error_code ec;
	if (fs::is_directory(path, ec))
		throw std::runtime_error(what + ": is a folder (give a file name)");
	if (!extensions.empty())
	{
		std::string ext = fs::path(path).extension().string();
		for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
		if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
		{
			std::string list;
			for (const auto& e : extensions) list += (list.empty() ? "" : ", ") + e;
			throw std::runtime_error(what + ": unsupported extension '" + ext + "' (use one of " +
			                         list + ")");
		}
	}
	if (fs::exists(path, ec) && ::access(path.c_str(), W_OK) != 0)
		throw std::runtime_error(what + ": the file exists and is not writable");
	const fs::path parent = fs::path(path).parent_path();
	if (const std::string why = whyNotUsable(parent.empty() ? "." : parent.string()); !why.empty())
		throw std::runtime_error(what + ": cannot write there: " + why);
}

std::string timeBaseWarning(const TFilterRun& run, const io::TGroundTruth& gt)
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

io::TGroundTruth estimatesAsReference(const TFilterRun& run)
{
	io::TGroundTruth g;
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
