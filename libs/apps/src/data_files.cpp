#include <dynslam/apps/data_files.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <mrpt/config/CConfigFile.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace dynslam::apps
{
namespace
{
std::string exeDir()
{
	std::error_code ec;
	const fs::path p = fs::read_symlink("/proc/self/exe", ec);
	return ec ? std::string() : p.parent_path().string();
}
bool isFile(const std::string& p)
{
	std::error_code ec;
	return fs::is_regular_file(p, ec);
}
bool endsWith(const std::string& s, const std::string& suffix)
{
	return s.size() >= suffix.size() &&
	       s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
std::string stripRawlogExt(const std::string& rawlogPath)
{
	fs::path p(rawlogPath);
	if (p.extension() == ".gz") p.replace_extension();
	if (p.extension() == ".rawlog") p.replace_extension();
	return p.string();
}
}  // namespace

std::vector<std::string> shippedFileCandidates(const std::string& relPath)
{
	std::vector<std::string> c{relPath};
	if (const std::string d = exeDir(); !d.empty())
		c.push_back(
		    (fs::path(d) / ".." / "share" / "dynslam" / relPath).lexically_normal().string());
#ifdef DYNSLAM_SOURCE_DIR
	c.push_back((fs::path(DYNSLAM_SOURCE_DIR) / relPath).lexically_normal().string());
#endif
	return c;
}

std::string locateShippedFile(const std::string& relPath)
{
	const auto c = shippedFileCandidates(relPath);
	for (const auto& p : c)
		if (isFile(p)) return p;
	std::string msg = "cannot find the shipped file '" + relPath + "'; tried:";
	for (const auto& p : c) msg += " " + p;
	throw std::runtime_error(msg);
}

std::string resolvePath(const std::string& p, const std::string& baseDir)
{
	if (p.empty() || fs::path(p).is_absolute() || baseDir.empty()) return p;
	return (fs::path(baseDir) / p).lexically_normal().string();
}

std::string folderOf(const std::string& path)
{
	const fs::path d = fs::path(path).parent_path();
	return d.empty() ? std::string(".") : d.string();
}

std::string TGroundTruthSpec::str() const { return (fs::path(dir) / base).string(); }

TGroundTruthSpec parseGroundTruthSpec(const std::string& spec)
{
	if (spec.empty()) throw std::runtime_error("empty ground-truth spec (expected DIR/BASE)");
	std::string s = spec;
	for (const char* suffix : {"_gt_ego.csv", "_gt_ego.tum", "_gt_landmarks.csv", "_gt_objects.csv",
	                           "_gt_object_features.csv"})
		if (endsWith(s, suffix))
		{
			s.resize(s.size() - std::string(suffix).size());
			break;
		}
	const fs::path p(s);
	TGroundTruthSpec out;
	out.dir = p.parent_path().empty() ? "." : p.parent_path().string();
	out.base = p.filename().string();
	if (out.base.empty())
		throw std::runtime_error("ground-truth spec '" + spec +
		                         "' has no base name (expected DIR/BASE)");
	return out;
}

std::string groundTruthBesideRawlog(const std::string& rawlogPath)
{
	const std::string b = stripRawlogExt(rawlogPath);
	if (isFile(b + "_gt_ego.csv")) return b;
	const std::string mrpt = rawlogPath + "_ground_truth_robot_path.txt";  // simul-landmarks
	return isFile(mrpt) ? mrpt : std::string();
}

namespace
{
const char* const kMrptPathSuffixes[2][2] = {
    {"_ground_truth_robot_path.txt", "_ground_truth.txt"},  // simul-landmarks
    {"_gt_robot_path.txt", "_gt_landmarks.txt"}};           // dynslam-simulate (kf-slam files)
}

bool isMrptGroundTruthSpec(const std::string& spec)
{
	for (const auto& s : kMrptPathSuffixes)
		if (endsWith(spec, s[0])) return true;
	return false;
}

std::string mrptLandmarksFileFor(const std::string& robotPathFile)
{
	for (const auto& s : kMrptPathSuffixes)
		if (endsWith(robotPathFile, s[0]))
			return robotPathFile.substr(0, robotPathFile.size() - std::string(s[0]).size()) + s[1];
	throw std::runtime_error("'" + robotPathFile +
	                         "' is not an MRPT robot-path ground-truth file name (expected "
	                         "..._ground_truth_robot_path.txt or ..._gt_robot_path.txt)");
}

std::string scenarioBesideRawlog(const std::string& rawlogPath)
{
	return stripRawlogExt(rawlogPath) + "_scenario.ini";
}

io::TGroundTruth loadGroundTruthFor(const std::string& spec, size_t rawlogSteps,
                                    const std::string& rawlogPath)
{
	const TGroundTruthSpec s = parseGroundTruthSpec(spec);
	const std::string egoFile = (fs::path(s.dir) / (s.base + "_gt_ego.csv")).string();
	if (!isFile(egoFile))
		throw std::runtime_error(
		    "ground truth '" + s.str() + "': " + egoFile +
		    " not found (expected the files DIR/BASE_gt_*.csv written by dynslam-simulate)");
	io::TGroundTruth gt;
	try
	{
		gt = io::readGroundTruth(s.dir, s.base);
		gt.checkConsistent();
	}
	catch (const std::exception& e)
	{
		throw std::runtime_error("ground truth '" + s.str() + "': " + e.what());
	}
	if (gt.numSteps() != rawlogSteps)
	{
		std::ostringstream msg;
		msg << "ground truth '" << s.str() << "' does not match rawlog '" << rawlogPath
		    << "': it has " << gt.numSteps() << " steps, the rawlog has " << rawlogSteps
		    << " action/observation pairs (one ground-truth step per pair expected)";
		throw std::runtime_error(msg.str());
	}
	return gt;
}

std::vector<std::pair<double, double>> highwayLandmarkGaps(const std::string& scenarioPath)
{
	std::error_code ec;
	if (scenarioPath.empty() || !std::filesystem::is_regular_file(scenarioPath, ec)) return {};
	if (!mrpt::config::CConfigFile(scenarioPath).keyExists("Scenario", "landmark_gaps")) return {};
	const sim::TScenarioOptions o = sim::loadScenario(scenarioPath);
	if (o.type != sim::ScenarioType::Highway) return {};
	return o.landmark_gaps;
}

TScenarioNoise readScenarioNoise(const std::string& path)
{
	if (!isFile(path)) throw std::runtime_error("scenario file '" + path + "' not found");
	TScenarioNoise n;
	n.file = path;
	try
	{
		mrpt::config::CConfigFile ini(path);
		const std::string s = "Noise";
		using namespace dynslam::config;
		n.level = readString(ini, s, "level", "custom");
		n.Sigma_w = readCovariance(ini, s, "sigma_w", n.Sigma_w, 3, true, true);
		n.Sigma_v = readCovariance(ini, s, "sigma_v", n.Sigma_v, 2, true, true);
		n.Sigma_0 = readCovariance(ini, s, "sigma_0", n.Sigma_w, 3, false, true);
		n.std_range = readNonNegative(ini, s, "std_range", 0, true);
		n.std_yaw_deg = readNonNegative(ini, s, "std_yaw_deg", 0, true);
	}
	catch (const std::exception& e)
	{
		throw std::runtime_error("scenario file '" + path + "': " + e.what());
	}
	return n;
}

std::string applyScenarioNoise(mrpt::config::CConfigFileMemory& ini, const TScenarioNoise& n,
                               const std::string& dynSection, const std::string& staticSection)
{
	using dynslam::config::formatMatrix;
	std::ostringstream what;
	what << "noise from " << n.file << " (level " << n.level << "):";
	if (!dynSection.empty())
	{
		const std::string model = ini.read_string(dynSection, "measurement_model", "cartesian");
		Eigen::Matrix2d Sv = n.Sigma_v;
		if (model == "range_bearing")
		{
			const double sy = n.std_yaw_deg * M_PI / 180.0;
			Sv = Eigen::Vector2d(n.std_range * n.std_range, sy * sy).asDiagonal();
		}
		ini.write(dynSection, "Sigma_v", formatMatrix(Sv));
		ini.write(dynSection, "Sigma_0", formatMatrix(n.Sigma_0));
		what << " [" << dynSection << "] Sigma_v, Sigma_0";
		if (ini.read_string(dynSection, "motion_noise", "action") == "config")
		{
			ini.write(dynSection, "Sigma_w", formatMatrix(n.Sigma_w));
			what << ", Sigma_w";
		}
	}
	if (!staticSection.empty())
	{
		std::ostringstream r, y;
		r.precision(17);
		y.precision(17);
		r << n.std_range;
		y << n.std_yaw_deg;
		ini.write(staticSection, "std_sensor_range", r.str());
		ini.write(staticSection, "std_sensor_yaw_deg", y.str());
		what << " [" << staticSection << "] std_sensor_range = " << n.std_range
		     << ", std_sensor_yaw_deg = " << n.std_yaw_deg;
	}
	return what.str();
}
}  // namespace dynslam::apps
