#pragma once
/** @file app_support.h
 * What every app class of the project does with its command line and its INI file. */
#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace TCLAP
{
class CmdLine;
}

namespace dynslam
{
/** Parses a TCLAP command line of app `app` (MRPT's bundled TCLAP): true to go on, false if
 * --help or --version was shown (the app exits 0). On an error TCLAP's own text ("PARSE ERROR",
 * the usage) is not printed; throws std::invalid_argument("app: bad command line: ARG: PROBLEM
 * (see app --help)"), e.g. "--runs: 'abc' is not a valid value". */
bool parseCommandLine(TCLAP::CmdLine& cmd, int argc, const char** argv, const std::string& app);

/** For an app whose TCLAP parse returned false (MRPT's bundled TCLAP returns false both for
 * --help/--version and for errors, after printing them): true if -h, --help or --version was
 * asked (the app exits 0); otherwise throws std::invalid_argument("app: bad command line (see
 * app --help)"). */
bool helpOrVersionAsked(int argc, const char** argv, const std::string& app);

/** `msg` prefixed by "config file 'iniFile': " unless it already names the file. */
std::string inConfigFile(const std::string& iniFile, const std::string& msg);

/** Loads section `section` of the INI file `iniFile` into `o` (its loadFromConfigFile): throws
 * std::runtime_error if the file does not exist, and every INI error names the file. */
template <class TOptions>
void loadSectionOfFile(const std::string& iniFile, const std::string& section, TOptions& o)
{
	if (!std::filesystem::is_regular_file(iniFile))
		throw std::runtime_error(iniFile + ": config file not found");
	try
	{
		mrpt::config::CConfigFile ini(iniFile);
		o.loadFromConfigFile(ini, section);
	}
	catch (const std::exception& e)
	{
		throw std::invalid_argument(inConfigFile(iniFile, e.what()));
	}
}
}  // namespace dynslam
