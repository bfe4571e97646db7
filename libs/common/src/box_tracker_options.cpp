/** TBoxTrackerOptions: section [BoxTracker]. */
#include <dynslam/common/box_tracker_options.h>
#include <dynslam/common/config_utils.h>

#include <ostream>
#include <stdexcept>

namespace dynslam
{
estimator::TBoxTrackerParams ab3dmotParams()
{
	estimator::TBoxTrackerParams p;
	p.metric = "bev_iou";
	p.min_iou = 0.01;
	p.min_hits = 3;
	p.max_age = 2;
	p.birth_window = p.min_hits + (p.min_hits - 1) * (p.max_age - 1);
	return p;
}

void TBoxTrackerOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                            const std::string& s)
{
	using namespace dynslam::config;
	rejectUnknownKeys(c, s,
	                  {"metric", "gate_prob", "min_iou", "min_hits", "birth_window", "max_age",
	                   "min_score", "accel_std", "yaw_std", "extent_std", "velocity_std",
	                   "meas_std", "report_lost", "report_first_frames"});
	estimator::TBoxTrackerParams& p = params;
	const std::vector<std::string> metrics{"mahalanobis", "bev_iou"};
	p.metric = metrics[size_t(readChoice(c, s, "metric", metrics, p.metric == "bev_iou" ? 1 : 0))];
	p.gate_prob = readPositive(c, s, "gate_prob", p.gate_prob);
	p.min_iou = readPositive(c, s, "min_iou", p.min_iou);
	p.min_hits = int(readInt(c, s, "min_hits", p.min_hits));
	p.birth_window = int(readInt(c, s, "birth_window", p.birth_window));
	p.max_age = int(readInt(c, s, "max_age", p.max_age));
	p.min_score = readDouble(c, s, "min_score", p.min_score);
	p.accel_std = readPositive(c, s, "accel_std", p.accel_std);
	p.yaw_std = readPositive(c, s, "yaw_std", p.yaw_std);
	p.extent_std = readPositive(c, s, "extent_std", p.extent_std);
	p.velocity_std = readPositive(c, s, "velocity_std", p.velocity_std);
	p.meas_std = readVector(c, s, "meas_std", p.meas_std, 5);
	report_lost = readBool(c, s, "report_lost", report_lost);
	report_first_frames = readBool(c, s, "report_first_frames", report_first_frames);
	try
	{
		p.validate();
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument("[" + s + "] " + e.what());
	}
}

void TBoxTrackerOptions::dumpToTextStream(std::ostream& out) const
{
	const estimator::TBoxTrackerParams& p = params;
	out << "\n----------- [TBoxTrackerOptions] ------------\n\n";
	out << "metric                         = " << p.metric << "\n";
	out << "gate_prob                      = " << p.gate_prob << "\n";
	out << "min_iou                        = " << p.min_iou << "\n";
	out << "min_hits                       = " << p.min_hits << "\n";
	out << "birth_window                   = " << p.birth_window << "\n";
	out << "max_age                        = " << p.max_age << "\n";
	out << "min_score                      = " << p.min_score << "\n";
	out << "accel_std                      = " << p.accel_std << "\n";
	out << "yaw_std                        = " << p.yaw_std << "\n";
	out << "extent_std                     = " << p.extent_std << "\n";
	out << "velocity_std                   = " << p.velocity_std << "\n";
	out << "meas_std                       = " << config::formatMatrix(p.meas_std.transpose())
	    << "\n";
	out << "report_lost                    = " << (report_lost ? "true" : "false") << "\n";
	out << "report_first_frames            = " << (report_first_frames ? "true" : "false") << "\n";
}
bool TBoxTrackerOptions::reports(const estimator::TBoxTrack& t, int frame) const
{
	const bool confirmedNow = t.state == estimator::ETrackState::Confirmed && t.updated;
	const bool lost = report_lost && t.state == estimator::ETrackState::Lost;
	return confirmedNow || lost || (report_first_frames && frame <= params.min_hits);
}
}  // namespace dynslam
