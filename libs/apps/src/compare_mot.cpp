#include "compare_mot.h"

#include <dynslam/core/models/se2.h>
#include <dynslam/io/box_ground_truth.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace dynslam::apps::detail
{
namespace
{
/** max_range and fov_deg of the importer's `<base>_scenario.ini` (0: not there). */
void readRegion(const std::string& base, double& maxRange, double& fov)
{
	std::ifstream f(base + "_scenario.ini");
	std::string line;
	while (std::getline(f, line))
	{
		std::istringstream ss(line);
		std::string key, eq;
		double v = 0;
		if (!(ss >> key >> eq >> v) || eq != "=") continue;
		if (key == "max_range") maxRange = v;
		if (key == "fov_deg") fov = v * M_PI / 180.0;
	}
}

bool inRegion(const Eigen::Vector3d& p, double maxRange, double fov)
{
	const double r = p.head<2>().norm();
	if (maxRange > 0 && r > maxRange) return false;
	return !(fov > 0 && std::abs(std::atan2(p.y(), p.x())) > fov / 2);
}

eval::TBevBox bev(const Eigen::Vector3d& p, const Eigen::Vector2d& e)
{
	return {p.x(), p.y(), p.z(), e.x(), e.y()};
}

bool matches(const eval::TBevBox& a, const eval::TBevBox& b, const eval::TMotOptions& o)
{
	return o.criterion == eval::EMotCriterion::BevIoU
	           ? eval::bevIoU(a, b) >= o.min_iou
	           : eval::bevCentreDistance(a, b) <= o.max_distance;
}

/** The frames of one criterion: hypotheses that match a neighbour and no truth left out. */
std::vector<eval::TMotFrame> frames(const TMotTruth& t,
                                    const std::vector<std::vector<TTrackedBox>>& hyp,
                                    const eval::TMotOptions& o)
{
	std::vector<eval::TMotFrame> out(t.truth.size());
	for (size_t k = 0; k < out.size(); ++k)
	{
		out[k].truth = t.truth[k];
		if (k >= hyp.size()) continue;
		for (const TTrackedBox& h : hyp[k])
		{
			if (h.cls != t.cls || !inRegion(h.pose, t.max_range, t.fov)) continue;
			const eval::TBevBox b = bev(h.pose, h.extent);
			const auto hit = [&](const eval::TMotObject& x) { return matches(b, x.box, o); };
			if (std::none_of(t.truth[k].begin(), t.truth[k].end(), hit) &&
			    std::any_of(t.ignored[k].begin(), t.ignored[k].end(), hit))
				continue;
			out[k].hyp.push_back({h.track, h.cls, b, h.score});
		}
	}
	return out;
}
}  // namespace

TMotTruth loadMotTruth(const std::string& base, const io::TGroundTruth& gt)
{
	TMotTruth t;
	if (!io::hasBoxGroundTruth(base)) return t;
	readRegion(base, t.max_range, t.fov);
	t.truth.resize(gt.numSteps());
	t.ignored.resize(gt.numSteps());
	for (const io::TTruthBox& b : io::readBoxGroundTruth(base))
	{
		if (size_t(b.step) >= gt.numSteps())
			throw std::runtime_error(base + "_gt_tracks.csv: step " + std::to_string(b.step) +
			                         " beyond the ground truth's " + std::to_string(gt.numSteps()) +
			                         " steps");
		const bool own = b.type == t.cls;
		const bool neighbour =
		    std::find(t.neighbours.begin(), t.neighbours.end(), b.type) != t.neighbours.end();
		if (!own && !neighbour) continue;
		const Eigen::Vector3d p = models::poseDifference(b.world, gt.ego[size_t(b.step)]);
		if (!inRegion(p, t.max_range, t.fov)) continue;
		(own ? t.truth : t.ignored)[size_t(b.step)].push_back(
		    {b.track, t.cls, bev(p, b.extent), 0});
	}
	t.valid = true;
	return t;
}

eval::TMetricsRow::TMotScores scoreMot(const TMotTruth& truth,
                                       const std::vector<std::vector<TTrackedBox>>& hyp)
{
	eval::TMetricsRow::TMotScores s;
	s.cls = truth.cls;
	eval::TMotOptions iou;
	iou.criterion = eval::EMotCriterion::BevIoU;
	eval::TMotOptions dist;
	dist.criterion = eval::EMotCriterion::CentreDistance;
	const auto fi = frames(truth, hyp, iou);
	s.iou = eval::clearMot(fi, iou);
	s.samota = eval::samota(fi, iou).samota;
	s.dist = eval::clearMot(frames(truth, hyp, dist), dist);
	return s;
}
std::string motLine(const std::string& filter, const eval::TMetricsRow::TMotScores& s)
{
	char buf[400];
	std::snprintf(buf, sizeof buf,
	              "tracking (%s, %zu truth boxes): %s: MOTA %.4f MOTP %.3f IDS %zu FRAG %zu FP %zu "
	              "FN %zu sAMOTA %.4f (BEV IoU >= 0.25); MOTA %.4f IDS %zu (centre <= 2 m)",
	              s.cls.c_str(), s.iou.gt, filter.c_str(), s.iou.mota, s.iou.motp, s.iou.ids,
	              s.iou.frag, s.iou.fp, s.iou.fn, s.samota, s.dist.mota, s.dist.ids);
	return buf;
}
}  // namespace dynslam::apps::detail
