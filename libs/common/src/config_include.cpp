/** `@include` for INI files: readIniText (config_include.h). */
#include <dynslam/common/config_include.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::config
{
namespace
{
namespace fs = std::filesystem;

std::string trimmed(const std::string& s)
{
	const size_t a = s.find_first_not_of(" \t\r");
	if (a == std::string::npos) return {};
	const size_t b = s.find_last_not_of(" \t\r");
	return s.substr(a, b - a + 1);
}

[[noreturn]] void failAt(const std::string& file, int line, const std::string& what)
{
	throw std::runtime_error("config file '" + file + "'" +
	                         (line > 0 ? " line " + std::to_string(line) : std::string()) + ": " +
	                         what);
}

std::string chainOf(const std::vector<std::string>& stack, const std::string& last)
{
	std::string c;
	for (const std::string& f : stack) c += f + " -> ";
	return c + last;
}

/** Whether a line is `@include PATH [# comment]`; its PATH ("" if none). */
bool includeDirective(const std::string& line, std::string& path)
{
	static const std::string kWord = "@include";
	if (line.compare(0, kWord.size(), kWord) != 0) return false;
	const std::string rest = line.substr(kWord.size());
	if (!rest.empty() && rest[0] != ' ' && rest[0] != '\t') return false;  // e.g. @included
	path = trimmed(rest.substr(0, rest.find_first_of("#;")));              // a trailing comment
	return true;
}

struct TExpander
{
	std::vector<std::string> stack;  ///< canonical paths of the files being read
	std::vector<std::string>* files = nullptr;

	void expand(const std::string& path, const std::string& from, int fromLine, std::string& out)
	{
		std::error_code ec;
		if (!fs::is_regular_file(path, ec))
		{
			if (stack.empty()) failAt(path, 0, "not found");
			failAt(from, fromLine, "@include '" + path + "': file not found");
		}
		const std::string canon = fs::weakly_canonical(path, ec).string();
		for (const std::string& f : stack)
			if (f == canon) failAt(from, fromLine, "circular @include: " + chainOf(stack, canon));
		if (int(stack.size()) > kMaxIncludeDepth)
			failAt(from, fromLine,
			       "@include nested deeper than " + std::to_string(kMaxIncludeDepth) + ": " +
			           chainOf(stack, canon));
		std::ifstream in(path, std::ios::binary);
		if (!in) failAt(path, 0, "cannot be read");
		if (files) files->push_back(path);
		stack.push_back(canon);
		expandLines(path, in, out);
		stack.pop_back();
	}

	void expandLines(const std::string& path, std::istream& in, std::string& out)
	{
		bool sawSection = false, sawInclude = false;
		std::string line;
		for (int n = 1; std::getline(in, line); ++n)
		{
			const std::string t = trimmed(line);
			std::string inc;
			if (includeDirective(t, inc))
			{
				if (inc.empty()) failAt(path, n, "@include without a file name");
				if (sawSection)
					failAt(path, n,
					       "@include after a section header (includes come first, "
					       "doc/configuration.md)");
				sawInclude = true;
				const fs::path p(inc);
				const fs::path target = p.is_absolute() ? p : fs::path(path).parent_path() / p;
				out += "; @include " + inc + "\n";
				expand(target.string(), path, n, out);
				out += "; end of @include " + inc + "\n";
				continue;
			}
			if (!t.empty() && t[0] == '[') sawSection = true;
			const bool key = !t.empty() && t[0] != ';' && t[0] != '#' && t[0] != '[' &&
			                 t.compare(0, 7, "@define") != 0;
			if (key && sawInclude && !sawSection)
				failAt(path, n,
				       "'" + t +
				           "' after an @include and before the first section header: it "
				           "would belong to the included file's last section");
			out += line;
			out += '\n';
		}
	}
};
}  // namespace

std::string readIniText(const std::string& path, std::vector<std::string>* files)
{
	TExpander e;
	e.files = files;
	std::string out;
	e.expand(path, "", 0, out);
	return out;
}

void loadIniWithIncludes(const std::string& path, mrpt::config::CConfigFileMemory& out,
                         std::vector<std::string>* files)
{
	out.setContent(readIniText(path, files));
}

std::vector<std::string> overlayProfile(const mrpt::config::CConfigFileMemory& base,
                                        const std::string& profile,
                                        const std::vector<std::string>& sections,
                                        mrpt::config::CConfigFileMemory& out)
{
	mrpt::config::CConfigFileMemory prof;
	loadIniWithIncludes(profile, prof);
	std::vector<std::string> first;
	if (!sections.empty()) prof.getAllKeys(sections.front(), first);
	if (first.empty())
		failAt(profile, 0,
		       "no section [" + (sections.empty() ? std::string() : sections.front()) +
		           "] (or it is empty): not a profile of it");
	out.setContent(base.getContent());
	std::vector<std::string> written;
	for (const std::string& section : sections)
	{
		std::vector<std::string> keys;
		prof.getAllKeys(section, keys);
		for (const std::string& k : keys)
		{
			out.write(section, k, prof.read_string(section, k, ""));
			written.push_back("[" + section + "] " + k);
		}
	}
	return written;
}
}  // namespace dynslam::config
