/** @file rawlog_format2.cpp
 * Observations-only rawlogs (MRPT format #2: CObservationOdometry + CObservationBearingRange)
 * converted into the (action, sensory frame) pairs of the back-ends; the odometry noise model
 * (MRPT's Gaussian motion model). See rawlog_io.h. */
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/common/config_utils.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "rawlog_detail.h"

namespace dynslam::apps
{
void TOdometryNoiseOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                               const std::string& s)
{
	using namespace dynslam::config;
	rejectUnknownKeys(c, s, {"model", "a1", "a2", "a3", "a4", "minStdXY", "minStdPHI_deg"});
	readChoice(c, s, "model", {"gaussian"}, 0);  // MRPT's mmThrun gives particles: not supported
	a1 = readNonNegative(c, s, "a1", a1);
	a2 = readNonNegative(c, s, "a2", a2);
	a3 = readNonNegative(c, s, "a3", a3);
	a4 = readNonNegative(c, s, "a4", a4);
	minStdXY = readNonNegative(c, s, "minStdXY", minStdXY);
	minStdPHI = readNonNegative(c, s, "minStdPHI_deg", minStdPHI * 180 / M_PI) * M_PI / 180;
}

void TOdometryNoiseOptions::dumpToTextStream(std::ostream& out) const
{
	out << "model = gaussian\na1 = " << a1 << "\na2 = " << a2 << "\na3 = " << a3 << "\na4 = " << a4
	    << "\nminStdXY = " << minStdXY << "\nminStdPHI_deg = " << minStdPHI * 180 / M_PI << "\n";
}

namespace
{
struct TOdometry
{
	size_t entry;
	mrpt::Clock::time_point t;
	mrpt::poses::CPose2D pose;
};

std::string entryWhat(const std::string& path, size_t entry)
{
	return detail::rawlogWhat(path) + ": entry " + std::to_string(entry);
}

/** The odometry readings in file order, checked (timestamp present, non-decreasing, finite). */
std::vector<TOdometry> odometryReadings(const std::vector<detail::TEntry>& entries,
                                        const std::string& path)
{
	std::vector<TOdometry> odo;
	for (const auto& [entry, obj] : entries)
	{
		const auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obj);
		if (!o) continue;
		if (o->timestamp == INVALID_TIMESTAMP)
			throw std::runtime_error(entryWhat(path, entry) +
			                         ": CObservationOdometry without a timestamp (an "
			                         "observations-only rawlog pairs odometry and observations "
			                         "by time)");
		if (!std::isfinite(o->odometry.x()) || !std::isfinite(o->odometry.y()) ||
		    !std::isfinite(o->odometry.phi()))
			throw std::runtime_error(entryWhat(path, entry) + ": odometry pose not finite");
		if (!odo.empty() && o->timestamp < odo.back().t)
			throw std::runtime_error(entryWhat(path, entry) +
			                         ": odometry timestamps decrease (this reading is older "
			                         "than the one at entry " +
			                         std::to_string(odo.back().entry) + ")");
		odo.push_back({entry, o->timestamp, o->odometry});
	}
	return odo;
}

mrpt::obs::CActionCollection::Ptr makeAction(const mrpt::poses::CPose2D* increment,
                                             const TOdometryNoiseOptions& n,
                                             mrpt::Clock::time_point t)
{
	mrpt::obs::CActionRobotMovement2D act;
	if (increment)
	{
		mrpt::obs::CActionRobotMovement2D::TMotionModelOptions m;
		m.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
		m.gaussianModel = {n.a1, n.a2, n.a3, n.a4, n.minStdXY, n.minStdPHI};
		act.computeFromOdometry(*increment, m);
	}
	else  // the first step: no motion, no uncertainty (as dynslam-simulate writes ACT_0)
		act.poseChange = mrpt::poses::CPosePDFGaussian::Create(mrpt::poses::CPose2D(),
		                                                       mrpt::math::CMatrixDouble33());
	act.timestamp = t;
	auto acts = mrpt::obs::CActionCollection::Create();
	acts->insert(act);
	return acts;
}
}  // namespace

void detail::convertObservationsOnly(const std::vector<TEntry>& entries,
                                     const TOdometryNoiseOptions& noise, TRawlog& out)
{
	const std::string what = rawlogWhat(out.path);
	const std::vector<TOdometry> odo = odometryReadings(entries, out.path);
	std::vector<mrpt::Clock::time_point> odoTimes;
	for (const auto& o : odo) odoTimes.push_back(o.t);

	const TOdometry* prev = nullptr;
	mrpt::Clock::time_point lastObs{};
	size_t dropped = 0, firstDropped = 0;
	for (const auto& [entry, obj] : entries)
	{
		const auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservationBearingRange>(obj);
		if (!obs) continue;
		const size_t frame = out.framesInFile++;
		if (obs->timestamp == INVALID_TIMESTAMP)
			throw std::runtime_error(entryWhat(out.path, entry) +
			                         ": CObservationBearingRange without a timestamp");
		checkSensorPose(*obs, out.path, entry);
		if (frame > 0 && obs->timestamp < lastObs)
			throw std::runtime_error(entryWhat(out.path, entry) +
			                         ": bearing-range timestamps decrease (the file must be "
			                         "in time order)");
		lastObs = obs->timestamp;
		if (odo.empty())
			throw std::runtime_error(what +
			                         ": observations-only rawlog (format #2) with "
			                         "CObservationBearingRange but no CObservationOdometry: the "
			                         "motion between the observations is unknown");
		// The last odometry reading not after the observation.
		const auto it = std::upper_bound(odoTimes.begin(), odoTimes.end(), obs->timestamp);
		if (it == odoTimes.begin())
		{
			if (dropped++ == 0) firstDropped = entry;
			continue;
		}
		const TOdometry& cur = odo[size_t(it - odoTimes.begin()) - 1];
		const mrpt::poses::CPose2D inc = prev ? cur.pose - prev->pose : mrpt::poses::CPose2D();
		out.actions.push_back(makeAction(prev ? &inc : nullptr, noise, obs->timestamp));
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		out.frames.push_back(sf);
		out.frameIndex.push_back(frame);
		prev = &cur;
	}
	if (dropped > 0)
		out.warnings.push_back(what + ": " + std::to_string(dropped) +
		                       " bearing-range observation(s) before the first odometry reading "
		                       "dropped (the first at entry " +
		                       std::to_string(firstDropped) + ")");
}
}  // namespace dynslam::apps
