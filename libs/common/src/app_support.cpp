#include <dynslam/app_support.h>

namespace dynslam
{
bool helpOrVersionAsked(int argc, const char** argv, const std::string& app)
{
	for (int i = 1; i < argc; ++i)
	{
		const std::string a = argv[i];
		if (a == "-h" || a == "--help" || a == "--version") return true;
	}
	throw std::invalid_argument(app + ": bad command line (see " + app + " --help)");
}

std::string inConfigFile(const std::string& iniFile, const std::string& msg)
{
	if (msg.find(iniFile) != std::string::npos) return msg;
	return "config file '" + iniFile + "': " + msg;
}
}  // namespace dynslam
