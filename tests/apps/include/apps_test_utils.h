#pragma once
// Helpers of the app tests: fresh temporary folders, running an executable with its output
// captured, small file utilities.
#include <dynslam_test/temp_dir.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace apps_test
{
/** A fresh, empty folder for the current test (removed first if it exists), removed when the
 * test program ends (dynslam_test/temp_dir.h). */
inline std::string freshDir(const std::string& tag)
{
	const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
	const std::string name = std::string(info ? info->test_suite_name() : "x") + "_" +
	                         (info ? info->name() : "y") + "_" + tag;
	return dynslam_test::tempDir("apps_" + name);
}

struct TCommandResult
{
	int exitCode = -1;  ///< exit status; -1 if the process did not exit normally (crash)
	bool exitedNormally = false;
	std::string output;  ///< stdout and stderr
};

inline std::string readFile(const std::string& path)
{
	std::ifstream f(path, std::ios::binary);
	std::ostringstream ss;
	ss << f.rdbuf();
	return ss.str();
}

/** Runs `cmd` through the shell in folder `cwd` (if not empty), capturing stdout+stderr. */
inline TCommandResult runCommand(const std::string& cmd, const std::string& cwd = "")
{
	const std::string out = freshDir("cmd") + "/output.txt";
	std::string full = cmd + " > '" + out + "' 2>&1";
	if (!cwd.empty()) full = "cd '" + cwd + "' && " + full;
	const int status = std::system(full.c_str());
	TCommandResult r;
	r.exitedNormally = status != -1 && WIFEXITED(status);
	r.exitCode = r.exitedNormally ? WEXITSTATUS(status) : -1;
	r.output = readFile(out);
	return r;
}

inline std::vector<std::string> readLines(const std::string& path)
{
	std::ifstream f(path);
	std::vector<std::string> lines;
	for (std::string l; std::getline(f, l);) lines.push_back(l);
	return lines;
}

inline std::vector<std::string> splitCsv(const std::string& line)
{
	std::vector<std::string> out;
	std::string cur;
	for (char c : line)
		if (c == ',')
			out.push_back(cur), cur.clear();
		else
			cur += c;
	out.push_back(cur);
	return out;
}

inline bool isPng(const std::string& path)
{
	const std::string s = readFile(path);
	return s.size() > 8 && s.compare(1, 3, "PNG") == 0;
}

inline std::string dataset(const std::string& name)
{
	return std::string(DYNSLAM_DATASETS_DIR) + "/" + name;
}
inline std::string configFile(const std::string& name)
{
	return std::string(DYNSLAM_CONFIG_DIR) + "/" + name;
}

/** The text of the shipped INI `name` with every relative `@include PATH` made absolute (to
 * the shipped config folder), so that a test can write an edited copy to another folder. */
inline std::string shippedIniText(const std::string& name)
{
	const std::string text = readFile(configFile(name));
	return std::regex_replace(text, std::regex("(^|\\n)@include[ \\t]+([^/ \\t\\n])"),
	                          "$1@include " + std::string(DYNSLAM_CONFIG_DIR) + "/$2");
}

/** Writes `text` to `path`. */
inline void writeFile(const std::string& path, const std::string& text)
{
	std::ofstream f(path, std::ios::binary);
	f << text;
}

/** argv for an app class from a list of arguments (argv[0] = "app"). */
struct TArgs
{
	explicit TArgs(std::vector<std::string> a) : args(std::move(a))
	{
		args.insert(args.begin(), "app");
		for (const auto& s : args) ptrs.push_back(s.c_str());
	}
	int argc() const { return int(ptrs.size()); }
	const char** argv() { return ptrs.data(); }
	std::vector<std::string> args;
	std::vector<const char*> ptrs;
};
}  // namespace apps_test
