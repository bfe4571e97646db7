#include <dynslam/apps/CTrackerBaselineBackend.h>
#include <dynslam/core/models/se2.h>

#include <ostream>
#include <stdexcept>

namespace dynslam::apps
{
CTrackerBaselineBackend::CTrackerBaselineBackend() { reset(); }

void CTrackerBaselineBackend::loadOptions(const mrpt::config::CConfigFileBase& ini)
{
	m_options = TBoxTrackerOptions();
	m_options.loadFromConfigFile(ini, "BoxTracker");
	CDeadReckoningBackend::loadOptions(ini);  // resets
}

void CTrackerBaselineBackend::dumpOptions(std::ostream& out) const
{
	CDeadReckoningBackend::dumpOptions(out);
	out << "# [BoxTracker] (TBoxTrackerOptions)";
	m_options.dumpToTextStream(out);
}

void CTrackerBaselineBackend::reset()
{
	CDeadReckoningBackend::reset();
	m_tracker = std::make_unique<estimator::CBoxTracker>(m_options.params);
	m_lastStamp = std::numeric_limits<double>::quiet_NaN();
	m_reported.clear();
}

void CTrackerBaselineBackend::onStep(const estimator::TStepInput& in)
{
	m_reported.clear();
	if (!in.boxes.empty() && !std::isfinite(in.stamp))
		throw std::runtime_error(name() + ": step " + std::to_string(steps() - 1) +
		                         " has detector boxes but no time stamp (the tracker's dt)");
	if (std::isfinite(in.stamp) && std::isfinite(m_lastStamp) && in.stamp > m_lastStamp)
		m_tracker->predict(in.stamp - m_lastStamp);
	if (std::isfinite(in.stamp)) m_lastStamp = in.stamp;

	const Eigen::Vector3d sensor = models::composePose(egoMean(), in.sensor_pose);
	std::vector<estimator::TWorldBox> world(in.boxes.size());
	for (size_t b = 0; b < in.boxes.size(); ++b)
	{
		world[b].pose = models::composePose(sensor, in.boxes[b].pose);
		world[b].extent = in.boxes[b].extent;
		world[b].cls = in.boxes[b].cls;
		world[b].score = in.boxes[b].score;
	}
	m_tracker->update(world);

	for (const estimator::TBoxTrack& t : m_tracker->tracks())
	{
		if (!m_options.reports(t, steps())) continue;
		TTrackedBox o;
		o.track = t.id;
		o.cls = t.cls;
		o.score = t.score;
		// the robot frame of this step: ego^-1 (+) world
		o.pose = models::poseDifference(t.x.head<3>(), egoMean());
		o.extent = t.x.segment<2>(3);
		m_reported.push_back(o);
	}
}
}  // namespace dynslam::apps
