#include <dynslam/apps/rawlog_io.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
/** The "Message:" lines of an MRPT exception (outermost first), without the backtraces. */
std::string shortReason(const std::exception& e)
{
	std::istringstream in(mrpt::exception_to_str(e));
	std::string line, out;
	while (std::getline(in, line))
	{
		const auto p = line.find("Message:");
		if (p == std::string::npos) continue;
		std::string msg = line.substr(p + 8);
		msg.erase(0, msg.find_first_not_of(' '));
		if (!out.empty()) out += " <- ";
		out += msg;
	}
	if (out.empty())
	{
		out = e.what();
		if (const auto nl = out.find('\n'); nl != std::string::npos) out.resize(nl);
	}
	// Garbage input can put binary bytes in the message (e.g. a bogus class name).
	for (char& c : out)
		if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
	if (out.size() > 400) out = out.substr(0, 400) + "...";
	return out;
}
}  // namespace

TRawlog loadRawlog(const std::string& path)
{
	namespace fs = std::filesystem;
	const std::string what = "rawlog '" + path + "'";
	std::error_code ec;
	if (!fs::exists(path, ec)) throw std::runtime_error(what + ": file not found");
	if (fs::is_directory(path, ec)) throw std::runtime_error(what + ": is a directory, not a file");

	mrpt::io::CFileGZInputStream f;
	if (!f.open(path)) throw std::runtime_error(what + ": cannot open the file");
	auto ar = mrpt::serialization::archiveFrom(f);

	TRawlog out;
	out.path = path;
	mrpt::obs::CActionCollection::Ptr pendingAction;
	size_t pendingEntry = 0;
	for (;;)
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			ar >> obj;
		}
		catch (const mrpt::serialization::CExceptionEOF&)
		{
			break;  // clean end: EOF at an object boundary
		}
		catch (const std::exception& e)
		{
			std::ostringstream msg;
			msg << what << ": corrupt or truncated at entry " << out.entries << " (after "
			    << out.size() << " complete action/observation pairs): " << shortReason(e);
			throw std::runtime_error(msg.str());
		}
		const size_t entry = out.entries++;
		if (!obj) continue;
		if (auto act = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj))
		{
			// Like readActionObservationPair: a second action before any sensory frame
			// replaces the first.
			pendingAction = act;
			pendingEntry = entry;
		}
		else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
		{
			if (!pendingAction) continue;  // frames before the first action are skipped
			out.actions.push_back(pendingAction);
			out.frames.push_back(sf);
			pendingAction.reset();
		}
		// anything else (comments, format-#2 observations) is skipped
	}
	if (pendingAction)
		throw std::runtime_error(what + ": truncated: the action at entry " +
		                         std::to_string(pendingEntry) + " has no sensory frame after it (" +
		                         std::to_string(out.size()) + " complete pairs before it)");
	if (out.size() == 0)
		throw std::runtime_error(
		    what + ": no action/observation pair found (" + std::to_string(out.entries) +
		    " entries read); expected an MRPT rawlog in format #1 (CActionCollection, "
		    "CSensoryFrame, ...)");
	return out;
}
}  // namespace dynslam::apps
