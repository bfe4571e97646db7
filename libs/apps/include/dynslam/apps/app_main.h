#pragma once
/** @file app_main.h
 * The body of every app's main(): runs the app and turns an exception into one line on stderr,
 *   <program>: error: <message>
 * and exit code 1. The message is the exception's what(); MRPT exceptions (thrown with MRPT's
 * macros) keep MRPT's formatting with the call stack. std exceptions get no "non-MRPT
 * exception" banner, and a message that already starts with "<program>: " is not prefixed a
 * second time. */
#include <mrpt/core/exceptions.h>

#include <exception>
#include <iostream>
#include <string>

namespace dynslam::apps
{
/** The text of an exception for the user (see the file comment). */
inline std::string userErrorMessage(const std::exception& e, const std::string& program = {})
{
	std::string msg = dynamic_cast<const mrpt::ExceptionWithCallBackBase*>(&e) != nullptr
	                      ? mrpt::exception_to_str(e)
	                      : std::string(e.what());
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
