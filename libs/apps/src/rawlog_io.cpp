#include <dynslam/apps/rawlog_io.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "rawlog_detail.h"

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

void detail::checkSensorPose(const mrpt::obs::CObservationBearingRange& obs,
                             const std::string& path, size_t entry)
{
	const auto& p = obs.sensorLocationOnRobot;
	for (int i = 0; i < 6; ++i)
		if (!std::isfinite(p[i]))
			throw std::runtime_error(detail::rawlogWhat(path) + ": entry " + std::to_string(entry) +
			                         ": the bearing-range observation's sensorLocationOnRobot is "
			                         "not finite (x y z yaw pitch roll = " +
			                         p.asString() + ")");
	for (size_t i = 0; i < obs.sensedData.size(); ++i)
	{
		const auto& m = obs.sensedData[i];
		const char* bad = !std::isfinite(m.range)   ? "its range is not a number (NaN or Inf)"
		                  : !std::isfinite(m.yaw)   ? "its yaw is not a number (NaN or Inf)"
		                  : !std::isfinite(m.pitch) ? "its pitch is not a number (NaN or Inf)"
		                  : m.range < 0             ? "its range is negative"
		                                            : nullptr;
		if (bad)
			throw std::runtime_error(detail::rawlogWhat(path) + ": entry " + std::to_string(entry) +
			                         ": measurement " + std::to_string(i) + " (landmark ID " +
			                         std::to_string(m.landmarkID) + "): " + bad);
	}
}

void detail::pairActionsAndFrames(const std::vector<TEntry>& entries, TRawlog& out)
{
	const std::string what = detail::rawlogWhat(out.path);
	mrpt::obs::CActionCollection::Ptr pendingAction;
	size_t pendingEntry = 0, standalone = 0;
	std::string leading;  // the warning of a sensory frame at the start of the file
	for (const auto& [entry, obj] : entries)
	{
		if (auto act = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj))
		{
			if (pendingAction)
				out.warnings.push_back(
				    what + ": the action at entry " + std::to_string(pendingEntry) +
				    " is followed by another action (entry " + std::to_string(entry) +
				    ") before any sensory frame: the later one is used, as in "
				    "MRPT's CRawlog::readActionObservationPair");
			pendingAction = act;
			pendingEntry = entry;
		}
		else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
		{
			const size_t frame = out.framesInFile++;
			if (auto o = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>())
				detail::checkSensorPose(*o, out.path, entry);
			if (!pendingAction)
			{
				const std::string w =
				    what + ": the sensory frame at entry " + std::to_string(entry) +
				    " comes before any action: skipped, as MRPT's kf-slam does (MRPT's "
				    "simul-landmarks writes each step as sensory frame, then action)";
				// The first frame of the file: decided at the end (MRPT's order or not).
				if (out.frames.empty() && leading.empty())
					leading = w;
				else
					out.warnings.push_back(w);
				continue;
			}
			out.actions.push_back(pendingAction);
			out.frames.push_back(sf);
			out.frameIndex.push_back(frame);
			pendingAction.reset();
		}
		else if (std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj) &&
		         !std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(obj))
			++standalone;
	}
	// A leading frame and a trailing action and nothing else dropped: MRPT's simul-landmarks
	// order (SF_0 ACT_0 ... SF_N-1 ACT_N-1), not a defect of the file: notes, not warnings.
	const bool mrptOrder = !leading.empty() && pendingAction && out.warnings.empty();
	auto& to = mrptOrder ? out.notes : out.warnings;
	if (!leading.empty()) to.insert(to.begin(), leading);
	if (pendingAction)
		to.push_back(what + ": the action at entry " + std::to_string(pendingEntry) +
		             " has no sensory frame after it: ignored, as MRPT's kf-slam does (" +
		             std::to_string(out.size()) + " pairs before it)");
	if (standalone > 0)
		out.warnings.push_back(what + ": " + std::to_string(standalone) +
		                       " standalone observation(s) outside sensory frames ignored (the "
		                       "file is in format #1: actions and sensory frames)");
}

TRawlog loadRawlog(const std::string& path, const TOdometryNoiseOptions& odometryNoise)
{
	namespace fs = std::filesystem;
	const std::string what = detail::rawlogWhat(path);
	std::error_code ec;
	if (!fs::exists(path, ec)) throw std::runtime_error(what + ": file not found");
	if (fs::is_directory(path, ec)) throw std::runtime_error(what + ": is a directory, not a file");

	mrpt::io::CFileGZInputStream f;
	if (!f.open(path)) throw std::runtime_error(what + ": cannot open the file");
	auto ar = mrpt::serialization::archiveFrom(f);

	TRawlog out;
	out.path = path;
	std::vector<detail::TEntry> entries;
	bool hasActions = false, pending = false;
	size_t pairsSoFar = 0;  // format #1 pairs read so far (for the truncation message)
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
			    << pairsSoFar << " complete action/observation pairs): " << shortReason(e);
			throw std::runtime_error(msg.str());
		}
		const size_t entry = out.entries++;
		if (!obj) continue;
		if (std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj))
			hasActions = pending = true;
		else if (pending && std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
			pending = false, ++pairsSoFar;
		entries.push_back({entry, std::move(obj)});
	}
	if (hasActions)
		detail::pairActionsAndFrames(entries, out);
	else
	{
		out.format = TRawlog::Format::ObservationsOnly;
		detail::convertObservationsOnly(entries, odometryNoise, out);
	}
	if (out.size() == 0)
		throw std::runtime_error(
		    what + ": no action/observation pair found (" + std::to_string(out.entries) +
		    " entries read); expected an MRPT rawlog in format #1 (CActionCollection, "
		    "CSensoryFrame, ...) or format #2 (CObservationOdometry and CObservationBearingRange)");
	return out;
}
}  // namespace dynslam::apps
