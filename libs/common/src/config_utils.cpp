#include <dynslam/common/config_utils.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynslam::config
{
namespace
{
std::string trim(const std::string& s)
{
	const auto b = s.find_first_not_of(" \t\r\n");
	if (b == std::string::npos) return "";
	const auto e = s.find_last_not_of(" \t\r\n");
	return s.substr(b, e - b + 1);
}
std::string lower(std::string s)
{
	std::transform(s.begin(), s.end(), s.begin(),
	               [](unsigned char ch) { return std::tolower(ch); });
	return s;
}
/** The raw value, or "" if missing. MRPT strips comments after '//' and ';'? It keeps
 * everything after '='; we strip trailing '//' and '#' comments ourselves. */
std::string raw(const mrpt::config::CConfigFileBase& c, const std::string& s, const std::string& k)
{
	std::string v = c.read_string(s, k, "", false);
	for (const char* mark : {"//", "#"})
	{
		const auto p = v.find(mark);
		if (p != std::string::npos) v = v.substr(0, p);
	}
	return trim(v);
}
bool parseDouble(const std::string& s, double& out)
{
	if (s.empty()) return false;
	std::istringstream is(s);
	is >> out;
	if (is.fail()) return false;
	is >> std::ws;
	return is.eof();
}
std::vector<double> parseNumbers(const std::string& section, const std::string& key,
                                 const std::string& value)
{
	std::string s = value;
	for (char& ch : s)
		if (ch == '[' || ch == ']' || ch == ',' || ch == ';') ch = ' ';
	std::istringstream is(s);
	std::vector<double> v;
	std::string tok;
	while (is >> tok)
	{
		double d;
		if (!parseDouble(tok, d)) fail(section, key, value, "'" + tok + "' is not a number");
		v.push_back(d);
	}
	return v;
}
}  // namespace

/** False if the key is missing and optional; throws if it is missing and required. */
static bool present(const mrpt::config::CConfigFileBase& c, const std::string& section,
                    const std::string& key, bool required)
{
	if (c.keyExists(section, key)) return true;
	if (required)
		throw std::invalid_argument("[" + section + "] " + key + ": required key is missing");
	return false;
}

void fail(const std::string& section, const std::string& key, const std::string& value,
          const std::string& what)
{
	throw std::invalid_argument("[" + section + "] " + key + " = '" + value + "': " + what);
}

bool has(const mrpt::config::CConfigFileBase& c, const std::string& section, const std::string& key)
{
	return c.keyExists(section, key);
}

std::string requireString(const mrpt::config::CConfigFileBase& c, const std::string& section,
                          const std::string& key)
{
	present(c, section, key, true);
	const std::string v = raw(c, section, key);
	if (v.empty()) fail(section, key, v, "required key is empty");
	return v;
}

double readDouble(const mrpt::config::CConfigFileBase& c, const std::string& section,
                  const std::string& key, double def, bool required)
{
	if (!present(c, section, key, required)) return def;
	const std::string v = raw(c, section, key);
	double d;
	if (!parseDouble(v, d)) fail(section, key, v, "not a number");
	if (!std::isfinite(d)) fail(section, key, v, "not finite");
	return d;
}

long readInt(const mrpt::config::CConfigFileBase& c, const std::string& section,
             const std::string& key, long def, bool required)
{
	const double d = readDouble(c, section, key, double(def), required);
	if (d != std::floor(d) || std::abs(d) > 9e15)
		fail(section, key, raw(c, section, key), "not an integer");
	return long(d);
}

bool readBool(const mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, bool def, bool required)
{
	if (!present(c, section, key, required)) return def;
	const std::string v = lower(raw(c, section, key));
	if (v == "true" || v == "1" || v == "yes" || v == "on") return true;
	if (v == "false" || v == "0" || v == "no" || v == "off") return false;
	fail(section, key, v, "not a boolean (true/false)");
}

std::string readString(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::string& key, const std::string& def, bool required)
{
	if (!present(c, section, key, required)) return def;
	return raw(c, section, key);
}

double readPositive(const mrpt::config::CConfigFileBase& c, const std::string& section,
                    const std::string& key, double def, bool required)
{
	const double d = readDouble(c, section, key, def, required);
	if (!(d > 0)) fail(section, key, raw(c, section, key), "must be > 0");
	return d;
}

double readNonNegative(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::string& key, double def, bool required)
{
	const double d = readDouble(c, section, key, def, required);
	if (!(d >= 0)) fail(section, key, raw(c, section, key), "must be >= 0");
	return d;
}

Eigen::VectorXd readVector(const mrpt::config::CConfigFileBase& c, const std::string& section,
                           const std::string& key, const Eigen::VectorXd& def, int n, bool required)
{
	if (!present(c, section, key, required)) return def;
	const std::string v = raw(c, section, key);
	const auto nums = parseNumbers(section, key, v);
	if (int(nums.size()) != n)
		fail(section, key, v,
		     "expected " + std::to_string(n) + " numbers, got " + std::to_string(nums.size()));
	Eigen::VectorXd out(n);
	for (int i = 0; i < n; ++i)
	{
		if (!std::isfinite(nums[i])) fail(section, key, v, "not finite");
		out[i] = nums[i];
	}
	return out;
}

Eigen::MatrixXd readCovariance(const mrpt::config::CConfigFileBase& c, const std::string& section,
                               const std::string& key, const Eigen::MatrixXd& def, int dim,
                               bool required, bool allowSingular)
{
	if (!present(c, section, key, required)) return def;
	const std::string v = raw(c, section, key);
	const auto nums = parseNumbers(section, key, v);
	Eigen::MatrixXd M = Eigen::MatrixXd::Zero(dim, dim);
	if (int(nums.size()) == dim)
		for (int i = 0; i < dim; ++i) M(i, i) = nums[i];
	else if (int(nums.size()) == dim * dim)
		for (int i = 0; i < dim; ++i)
			for (int j = 0; j < dim; ++j) M(i, j) = nums[i * dim + j];
	else
		fail(section, key, v,
		     "expected a " + std::to_string(dim) + "x" + std::to_string(dim) +
		         " covariance: " + std::to_string(dim) + " diagonal entries or " +
		         std::to_string(dim * dim) + " entries");
	if (!M.allFinite()) fail(section, key, v, "not finite");
	if ((M - M.transpose()).cwiseAbs().maxCoeff() > 1e-12 * std::max(1.0, M.cwiseAbs().maxCoeff()))
		fail(section, key, v, "covariance is not symmetric");
	const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(M);
	const double lmin = es.eigenvalues().minCoeff();
	if (allowSingular ? lmin < 0 : !(lmin > 0))
		fail(section, key, v,
		     std::string("covariance is not positive ") + (allowSingular ? "semi-" : "") +
		         "definite (smallest eigenvalue " + std::to_string(lmin) + ")");
	return M;
}

int readChoice(const mrpt::config::CConfigFileBase& c, const std::string& section,
               const std::string& key, const std::vector<std::string>& choices, int def,
               bool required)
{
	if (!present(c, section, key, required)) return def;
	const std::string v = raw(c, section, key);
	for (size_t i = 0; i < choices.size(); ++i)
		if (lower(v) == lower(choices[i])) return int(i);
	std::string list;
	for (const auto& ch : choices) list += (list.empty() ? "" : ", ") + ch;
	fail(section, key, v, "unknown value (expected one of: " + list + ")");
}

void rejectUnknownKeys(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::vector<std::string>& known)
{
	// Case-insensitive, as MRPT's reader (SimpleIni's SI_GenericNoCase) finds the keys.
	const auto lower = [](std::string x)
	{
		for (char& ch : x) ch = char(std::tolower(static_cast<unsigned char>(ch)));
		return x;
	};
	std::vector<std::string> keys;
	c.getAllKeys(section, keys);
	for (const auto& k : keys)
		if (std::none_of(known.begin(), known.end(),
		                 [&](const std::string& n) { return lower(n) == lower(k); }))
			throw std::invalid_argument("[" + section + "] " + k + ": unknown key (misspelled?)");
}

std::string formatMatrix(const Eigen::MatrixXd& m)
{
	std::ostringstream os;
	os.precision(10);
	os << "[";
	for (Eigen::Index i = 0; i < m.rows(); ++i)
	{
		for (Eigen::Index j = 0; j < m.cols(); ++j) os << (j ? " " : "") << m(i, j);
		if (i + 1 < m.rows()) os << "; ";
	}
	os << "]";
	return os.str();
}
}  // namespace dynslam::config
