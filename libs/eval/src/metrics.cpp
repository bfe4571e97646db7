#include "dynslam/eval/metrics.h"

#include <dynslam/core/models/se2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "dynslam/eval/align.h"

namespace dynslam::eval
{
namespace
{
/// Accumulates squared errors per component.
struct TSq
{
	std::vector<double> x, y, theta;
	TRmse finish() const { return rmseOf(x, y, theta); }
};

}  // namespace

Eigen::Vector3d poseError(const Eigen::Vector3d& est, const Eigen::Vector3d& truth)
{
	Eigen::Vector3d e = est - truth;
	e[2] = models::wrapToPi(e[2]);
	return e;
}

double rmse(const std::vector<double>& errors)
{
	if (errors.empty()) return kNaN;
	double s = 0;
	for (double e : errors) s += e * e;
	return std::sqrt(s / static_cast<double>(errors.size()));
}

TRmse rmseOf(const std::vector<double>& x, const std::vector<double>& y,
             const std::vector<double>& theta)
{
	TRmse r;
	r.x = rmse(x);
	r.y = rmse(y);
	r.theta = rmse(theta);
	r.n_xy = x.size();
	r.n_theta = theta.size();
	return r;
}

void checkGroundTruth(const io::TGroundTruth& gt)
{
	const size_t n = gt.numSteps();
	if (!gt.t.empty() && gt.t.size() != n)
		throw std::invalid_argument("ground truth: " + std::to_string(gt.t.size()) +
		                            " time stamps for " + std::to_string(n) + " ego steps");
	for (const auto& o : gt.objects)
	{
		const std::string name = "ground truth object " + std::to_string(o.object);
		if (o.features.size() != n || o.pose.size() != n || o.visible.size() != n)
			throw std::invalid_argument(name + ": per-step vectors do not have " +
			                            std::to_string(n) + " entries");
		for (const auto& f : o.features)
			if (f.cols() != o.num_features)
				throw std::invalid_argument(name + ": feature matrix with " +
				                            std::to_string(f.cols()) + " columns, expected " +
				                            std::to_string(o.num_features));
		if (o.first_step >= static_cast<int>(n))
			throw std::invalid_argument(name + ": first_step beyond the last step");
	}
}

namespace
{
// Ego: every estimated step inside the ground truth; ATE unaligned and SE(2)-aligned.
void scoreEgo(const io::TGroundTruth& gt, const TRunEstimates& est, TRunMetrics& m)
{
	const int nSteps = static_cast<int>(gt.numSteps());
	TSq ego;
	double sumSqPos = 0;
	std::vector<Eigen::Vector2d> estXY, truthXY;
	for (const auto& e : est.ego)
	{
		if (e.step < 0 || e.step >= nSteps)
		{
			++m.ego_skipped;
			continue;
		}
		const Eigen::Vector3d d = poseError(e.mean, gt.ego[e.step]);
		ego.x.push_back(d[0]);
		ego.y.push_back(d[1]);
		ego.theta.push_back(d[2]);
		sumSqPos += d[0] * d[0] + d[1] * d[1];
		estXY.push_back(e.mean.head<2>());
		truthXY.push_back(gt.ego[e.step].head<2>());
	}
	m.ego = ego.finish();
	if (!ego.x.empty())
	{
		m.ate = std::sqrt(sumSqPos / static_cast<double>(ego.x.size()));
		m.ate_aligned = alignSE2(estXY, truthXY).rms;
	}
}

// Static map: final estimates of IDs present in the ground truth.
void scoreStaticMap(const io::TGroundTruth& gt, const TRunEstimates& est, TRunMetrics& m)
{
	TSq lm;
	std::set<int32_t> scored;
	for (const auto& l : est.landmarks)
	{
		const auto it = gt.landmarks.find(l.id);
		if (it == gt.landmarks.end())
		{
			++m.landmarks_unmatched;
			continue;
		}
		lm.x.push_back(l.mean[0] - it->second[0]);
		lm.y.push_back(l.mean[1] - it->second[1]);
		scored.insert(l.id);
	}
	m.static_map = lm.finish();
	m.landmarks_missing = gt.landmarks.size() - scored.size();
}

// One object: its time-0 features and its poses.
TObjectMetrics scoreObject(const io::TObjectGroundTruth& o, const TRunEstimates& est, int nSteps,
                           TRunMetrics& m)
{
	TObjectMetrics om;
	om.object = o.object;
	om.translation_only = o.translationOnly();
	TSq feat;
	std::set<int32_t> featScored;
	for (const auto& f : est.object_features)
	{
		if (f.object != o.object) continue;
		if (o.first_step < 0 || f.feature < 0 || f.feature >= o.num_features)
		{
			++m.object_estimates_unmatched;
			continue;
		}
		const Eigen::Vector2d truth = o.features[o.first_step].col(f.feature);
		feat.x.push_back(f.mean[0] - truth[0]);
		feat.y.push_back(f.mean[1] - truth[1]);
		featScored.insert(f.feature);
	}
	om.features = feat.finish();
	om.features_missing = static_cast<size_t>(o.num_features) - featScored.size();
	TSq pose;
	for (const auto& p : est.object_poses)
	{
		if (p.object != o.object) continue;
		if (p.step < 0 || p.step >= nSteps || !o.pose[p.step].allFinite())
		{
			++om.poses_skipped;
			continue;
		}
		const Eigen::Vector3d& truth = o.pose[p.step];
		pose.x.push_back(p.mean[0] - truth[0]);
		pose.y.push_back(p.mean[1] - truth[1]);
		if (p.mean.size() == 3) pose.theta.push_back(models::wrapToPi(p.mean[2] - truth[2]));
	}
	om.poses = pose.finish();
	return om;
}
}  // namespace

TRunMetrics computeRunMetrics(const io::TGroundTruth& gt, const TRunEstimates& est)
{
	checkEstimates(est);
	checkGroundTruth(gt);
	TRunMetrics m;
	m.ms_per_step = est.ms_per_step;
	if (est.odometry_bias.size() >= 1) m.odometry_bias_rate = est.odometry_bias[0];
	if (est.odometry_bias.size() >= 2) m.odometry_bias_scale = est.odometry_bias[1];
	scoreEgo(gt, est, m);
	scoreStaticMap(gt, est, m);
	std::set<int32_t> known;
	for (const auto& o : gt.objects)
	{
		known.insert(o.object);
		m.objects.push_back(scoreObject(o, est, static_cast<int>(gt.numSteps()), m));
	}
	for (const auto& f : est.object_features)
		if (!known.count(f.object)) ++m.object_estimates_unmatched;
	for (const auto& p : est.object_poses)
		if (!known.count(p.object)) ++m.object_estimates_unmatched;
	return m;
}

std::vector<TEgoErrorRow> egoErrors(const io::TGroundTruth& gt,
                                    const std::vector<TEgoEstimate>& ego)
{
	std::vector<TEgoErrorRow> rows;
	const int nSteps = static_cast<int>(gt.numSteps());
	for (const auto& e : ego)
	{
		if (e.step < 0 || e.step >= nSteps) continue;
		TEgoErrorRow r;
		r.step = e.step;
		r.t = std::isfinite(e.t)
		          ? e.t
		          : (static_cast<size_t>(e.step) < gt.t.size() ? gt.t[e.step] : kNaN);
		r.est = e.mean;
		r.truth = gt.ego[e.step];
		r.error = poseError(e.mean, r.truth);
		r.sigma3 = 3.0 * e.cov.diagonal().cwiseMax(0.0).cwiseSqrt();
		rows.push_back(r);
	}
	std::sort(rows.begin(), rows.end(),
	          [](const auto& a, const auto& b) { return a.step < b.step; });
	return rows;
}
}  // namespace dynslam::eval
