#pragma once
// Private helper of the app classes: parses a TCLAP command line with MRPT's bundled TCLAP,
// which returns false both for --help/--version and for errors (after printing them).
#include <dynslam/common/app_support.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <optional>
#include <stdexcept>
#include <string>

namespace dynslam::apps::detail
{
/** True: go on. False: --help or --version was shown. Throws std::invalid_argument with one
 * line naming the argument and the problem (dynslam::parseCommandLine). */
inline bool parseCommandLine(TCLAP::CmdLine& cmd, int argc, const char** argv,
                             const std::string& app)
{
	return dynslam::parseCommandLine(cmd, argc, argv, app);
}
/** The value of an optional argument, or nothing if it was not given (INI overrides). */
inline std::optional<std::string> valueIfSet(TCLAP::ValueArg<std::string>& a)
{
	return a.isSet() ? std::optional<std::string>(a.getValue()) : std::nullopt;
}
}  // namespace dynslam::apps::detail
