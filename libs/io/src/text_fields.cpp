#include <dynslam/io/text_fields.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace dynslam::io
{
void throwAtLine(const std::string& path, int line, const std::string& what)
{
	throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

std::vector<std::string> splitWhitespace(const std::string& s)
{
	std::vector<std::string> out;
	std::istringstream is(s);
	std::string tok;
	while (is >> tok) out.push_back(tok);
	return out;
}

double parseFiniteField(const std::string& tok, const std::string& path, int line, size_t col)
{
	const char* b = tok.c_str();
	char* e = nullptr;
	errno = 0;
	const double v = std::strtod(b, &e);
	const std::string column = "column " + std::to_string(col + 1) + ": ";
	if (e == b || *e != '\0') throwAtLine(path, line, column + "'" + tok + "' is not a number");
	if (!std::isfinite(v) || errno == ERANGE)
		throwAtLine(path, line, column + "non-finite value '" + tok + "'");
	return v;
}
}  // namespace dynslam::io
