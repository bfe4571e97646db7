#include <dynslam/common/app_support.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/3rdparty/tclap/StdOutput.h>

namespace dynslam
{
namespace
{
/** TCLAP's StdOutput (usage, version) that keeps a failure instead of printing it. */
class CQuietFailureOutput : public TCLAP::StdOutput
{
public:
	void failure(TCLAP::CmdLineInterface&, TCLAP::ArgException& e) override
	{
		failed = true;
		arg = e.argId();
		problem = e.error();
	}
	bool failed = false;
	std::string arg, problem;
};

/** "ARG: PROBLEM" in words for TCLAP's failure texts. */
std::string describeFailure(std::string arg, const std::string& problem)
{
	const std::string prefix = "Argument: ";
	if (arg.rfind(prefix, 0) == 0) arg.erase(0, prefix.size());
	while (!arg.empty() && arg.front() == ' ') arg.erase(0, 1);
	// TCLAP's "(--runs)" or "-n (--runs)": "--runs", "-n/--runs".
	if (!arg.empty() && arg.back() == ')')
	{
		arg.pop_back();
		const auto open = arg.find('(');
		if (open != std::string::npos)
			arg = arg.substr(0, open == 0 ? 0 : open - 1) + (open == 0 ? "" : "/") +
			      arg.substr(open + 1);
	}
	std::string what = problem;
	const std::string bad = "Couldn't read argument value from string ";
	if (problem.rfind(bad, 0) == 0)
		what = problem.substr(bad.size()) + " is not a valid value";
	else if (problem.find("Missing a value") != std::string::npos)
		what = "a value is missing";
	else if (problem.find("Couldn't find match") != std::string::npos)
		what = "unknown option or argument";
	else if (problem.find("required arguments missing") != std::string::npos)
		what = "a required option is missing";
	return arg.empty() ? what : arg + ": " + what;
}
}  // namespace

bool parseCommandLine(TCLAP::CmdLine& cmd, int argc, const char** argv, const std::string& app)
{
	static thread_local CQuietFailureOutput out;  // outlives cmd's use of it (parse only)
	out.failed = false;
	// The CmdLine's own StdOutput (allocated by its constructor, which deletes it only if no
	// output was set) is replaced: delete it here. Precondition: no output set before.
	TCLAP::CmdLineOutput* own = cmd.getOutput();
	cmd.setOutput(&out);
	if (own != &out) delete own;
	if (cmd.parse(argc, argv)) return true;
	if (!out.failed) return false;  // --help or --version
	std::string missing;            // TCLAP does not say which required option is missing
	for (TCLAP::Arg* a : cmd.getArgList())
		if (a->isRequired() && !a->isSet())
			missing += (missing.empty() ? " (" : ", ") + a->longID();
	std::string what = describeFailure(out.arg, out.problem);
	if (what == "a required option is missing" && !missing.empty()) what += missing + ")";
	throw std::invalid_argument(app + ": bad command line: " + what + " (see " + app + " --help)");
}

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
