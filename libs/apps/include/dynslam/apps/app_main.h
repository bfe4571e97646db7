#pragma once
/** @file app_main.h
 * The body of every app's main(): runs the app and turns an exception into one line on stderr,
 *   <program>: error: <message>
 * and exit code 1. The message is one line (oneLineReason): no exception banner, no call stack;
 * a message that already starts with "<program>: " is not prefixed a second time. */
#include <mrpt/core/exceptions.h>

#include <exception>
#include <iostream>
#include <sstream>
#include <string>

namespace dynslam::apps
{
/** One line for the user from any exception: MRPT's exceptions (thrown with MRPT's macros,
 * possibly nested) give their "Message:" lines joined by " <- ", without MRPT's banner, file
 * locations and call stack; other exceptions their what() (any "==== ... exception ===="
 * banner line dropped). Line breaks become "; ". */
inline std::string oneLineReason(const std::exception& e)
{
	const bool mrptException = dynamic_cast<const mrpt::ExceptionWithCallBackBase*>(&e) != nullptr;
	std::istringstream in(mrptException ? mrpt::exception_to_str(e) : std::string(e.what()));
	std::string line, out;
	bool sawMessage = false;
	while (std::getline(in, line))
	{
		const auto p = line.find("Message:");
		if (mrptException && p == std::string::npos) continue;
		if (p != std::string::npos) line = line.substr(p + 8), sawMessage = true;
		line.erase(0, line.find_first_not_of(' '));
		while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
		if (line.empty() || line.rfind("====", 0) == 0) continue;
		if (!out.empty()) out += mrptException ? " <- " : "; ";
		out += line;
	}
	if (mrptException && !sawMessage) out = e.what();
	return out;
}

/** The text of an exception for the user (see the file comment). */
inline std::string userErrorMessage(const std::exception& e, const std::string& program = {})
{
	std::string msg = oneLineReason(e);
	for (const std::string& p : {program + ": error: ", program + ": "})
		if (!program.empty() && msg.rfind(p, 0) == 0) msg.erase(0, p.size());
	while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
	return msg;
}

/** Runs body() (which returns the exit code) and reports an exception as described above. */
template <class Body>
int runMain(const std::string& program, Body&& body)
{
	try
	{
		return body();
	}
	catch (const std::exception& e)
	{
		std::cerr << program << ": error: " << userErrorMessage(e, program) << "\n";
		return 1;
	}
}
}  // namespace dynslam::apps
