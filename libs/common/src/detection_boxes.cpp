#include <dynslam/common/detection_boxes.h>

#include <Eigen/Core>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace dynslam
{
namespace
{
bool hasSpace(const std::string& s) { return s.find_first_of(" \t\r\n\v\f") != std::string::npos; }

/** The finite number of a token, or an error message (empty: fine). */
std::string parseNumber(const std::string& tok, double& v)
{
	errno = 0;
	char* end = nullptr;
	v = std::strtod(tok.c_str(), &end);
	if (end == tok.c_str() || *end != '\0') return "'" + tok + "' is not a number";
	if (!std::isfinite(v)) return "'" + tok + "' is not finite";
	return "";
}

/** One box line: "<group> <class> <score> <x> <y> <yaw> <length> <width>". */
estimator::TBoxDetection parseBoxLine(const std::string& line, const std::string& where)
{
	std::istringstream ls(line);
	std::vector<std::string> t;
	for (std::string w; ls >> w;) t.push_back(w);
	if (t.size() != 8)
		throw std::runtime_error(where +
		                         ": expected 8 columns '<group> <class> <score> <x> <y> "
		                         "<yaw> <length> <width>', found " +
		                         std::to_string(t.size()));
	estimator::TBoxDetection b;
	errno = 0;
	char* end = nullptr;
	const long long g = std::strtoll(t[0].c_str(), &end, 10);
	if (end == t[0].c_str() || *end != '\0' || errno == ERANGE)
		throw std::runtime_error(where + ": group '" + t[0] + "' is not an integer");
	if (g < 0 || g > INT32_MAX)
		throw std::runtime_error(where + ": group " + t[0] + " (an ID >= 0)");
	b.group = int32_t(g);
	b.cls = t[1];
	double v[6];
	static const char* names[6] = {"score", "x", "y", "yaw", "length", "width"};
	for (size_t i = 0; i < 6; ++i)
	{
		const std::string e = parseNumber(t[i + 2], v[i]);
		if (!e.empty()) throw std::runtime_error(where + ": " + names[i] + " " + e);
	}
	b.score = v[0];
	b.pose = Eigen::Vector3d(v[1], v[2], v[3]);
	b.extent = Eigen::Vector2d(v[4], v[5]);
	if (!(v[4] > 0 && v[5] > 0))
		throw std::runtime_error(where + ": length and width must be > 0 (" + t[6] + ", " + t[7] +
		                         ")");
	return b;
}

/** The text after the label line of SF's DETECTION_BOXES comment; false: none. */
bool findBoxesComment(const mrpt::obs::CSensoryFrame& SF, std::string& text)
{
	for (const auto& o : SF)
	{
		const auto c = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(o);
		if (!c) continue;
		std::istringstream in(c->text);
		std::string first;
		if (!std::getline(in, first)) continue;
		while (!first.empty() && (first.back() == '\r' || first.back() == ' ')) first.pop_back();
		if (first != kDetectionBoxesLabel) continue;  // another comment
		text = c->text;
		return true;
	}
	return false;
}
}  // namespace

mrpt::obs::CObservationComment::Ptr makeDetectionBoxes(
    const std::vector<estimator::TBoxDetection>& boxes)
{
	std::set<int32_t> groups;
	std::ostringstream t;
	t << kDetectionBoxesLabel << "\n# group class score x y yaw length width\n";
	t << std::setprecision(17);
	for (size_t i = 0; i < boxes.size(); ++i)
	{
		const auto& b = boxes[i];
		const std::string who = "makeDetectionBoxes: box " + std::to_string(i) + ": ";
		if (b.group < 0) throw std::invalid_argument(who + "group < 0");
		if (!groups.insert(b.group).second)
			throw std::invalid_argument(who + "group " + std::to_string(b.group) + " repeated");
		if (b.cls.empty() || hasSpace(b.cls))
			throw std::invalid_argument(who + "class '" + b.cls + "' (one word)");
		if (!std::isfinite(b.score) || !b.pose.allFinite() || !b.extent.allFinite())
			throw std::invalid_argument(who + "a number is not finite");
		if (!(b.extent.x() > 0 && b.extent.y() > 0))
			throw std::invalid_argument(who + "length and width must be > 0");
		t << b.group << ' ' << b.cls << ' ' << b.score << ' ' << b.pose.x() << ' ' << b.pose.y()
		  << ' ' << b.pose.z() << ' ' << b.extent.x() << ' ' << b.extent.y() << '\n';
	}
	auto c = mrpt::obs::CObservationComment::Create();
	c->sensorLabel = kDetectionBoxesLabel;
	c->text = t.str();
	return c;
}

std::vector<Eigen::Vector2d> boxCorners(const estimator::TBoxDetection& box)
{
	const double L = box.extent.x() / 2, W = box.extent.y() / 2;
	const double c = std::cos(box.pose.z()), s = std::sin(box.pose.z());
	const Eigen::Vector2d u(c, s), v(-s, c);  // length axis, and its left
	const Eigen::Vector2d p = box.pose.head<2>();
	return {p + L * u + W * v, p + L * u - W * v, p - L * u - W * v, p - L * u + W * v};
}

std::vector<estimator::TBoxDetection> readDetectionBoxes(const mrpt::obs::CSensoryFrame& SF,
                                                         const std::string& who)
{
	std::vector<estimator::TBoxDetection> boxes;
	std::string text;
	if (!findBoxesComment(SF, text)) return boxes;
	std::istringstream in(text);
	std::string line;
	std::getline(in, line);  // the label
	std::set<int32_t> groups;
	for (int n = 2; std::getline(in, line); ++n)
	{
		const auto first = line.find_first_not_of(" \t\r");
		if (first == std::string::npos || line[first] == '#') continue;
		const std::string where = who + ": " + kDetectionBoxesLabel + " comment, line " +
		                          std::to_string(n) + " '" + line + "'";
		boxes.push_back(parseBoxLine(line, where));
		if (!groups.insert(boxes.back().group).second)
			throw std::runtime_error(where + ": group " + std::to_string(boxes.back().group) +
			                         " repeated");
	}
	return boxes;
}
}  // namespace dynslam

namespace dynslam
{
void checkBoxCorners(const std::vector<estimator::TBoxDetection>& boxes,
                     const std::vector<estimator::TReading>& readings, const std::string& who)
{
	if (boxes.empty()) return;
	std::map<int32_t, std::pair<size_t, size_t>> n;  // group -> (readings, with ID -1)
	for (const auto& r : readings)
		if (r.hint >= 0)
		{
			auto& c = n[r.hint];
			++c.first;
			c.second += r.id == -1;
		}
	for (size_t i = 0; i < boxes.size(); ++i)
	{
		const auto& b = boxes[i];
		const auto it = n.find(b.group);
		const size_t all = it == n.end() ? 0 : it->second.first;
		const size_t unknown = it == n.end() ? 0 : it->second.second;
		if (all != 4 || unknown != 4)
			throw std::runtime_error(
			    who + ": " + kDetectionBoxesLabel + " box " + std::to_string(i) + " (group " +
			    std::to_string(b.group) + ", " + b.cls + "): " + std::to_string(all) +
			    " readings with that detection group, " + std::to_string(unknown) +
			    " of them with landmark ID -1; expected its 4 corners, "
			    "each with ID -1");
	}
}
}  // namespace dynslam
