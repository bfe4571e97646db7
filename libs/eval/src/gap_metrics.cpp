#include <dynslam/eval/chi2.h>
#include <dynslam/eval/gap_metrics.h>
#include <dynslam/eval/metrics.h>

#include <Eigen/Cholesky>
#include <cmath>

namespace dynslam::eval
{
namespace
{
bool inGap(double x, const std::vector<std::pair<double, double>>& gaps)
{
	for (const auto& [a, b] : gaps)
		if (x >= a && x <= b) return true;
	return false;
}
}  // namespace

TGapMetrics gapMetrics(const io::TGroundTruth& gt, const std::vector<TEgoEstimate>& ego,
                       const std::vector<std::pair<double, double>>& gaps)
{
	TGapMetrics g;
	std::vector<double> inside, outside;
	double neesSum = 0;
	int lastStep = -1;
	for (const TEgoEstimate& e : ego)
	{
		if (e.step < 0 || size_t(e.step) >= gt.numSteps()) continue;
		const Eigen::Vector3d err = poseError(e.mean, gt.ego[size_t(e.step)]);
		const double d = err.head<2>().norm();
		if (!inGap(gt.ego[size_t(e.step)].x(), gaps))
		{
			outside.push_back(d);
			continue;
		}
		inside.push_back(d);
		if (e.step > lastStep)
		{
			lastStep = e.step;
			g.err_end = d;
		}
		const Eigen::LLT<Eigen::Matrix3d> llt(e.cov);
		if (llt.info() != Eigen::Success) continue;  // e.g. a zero covariance: no NEES
		neesSum += err.dot(llt.solve(err));
		++g.nees_steps;
	}
	g.steps = inside.size();
	g.ate = rmse(inside);
	g.ate_outside = rmse(outside);
	if (g.nees_steps > 0)
	{
		const double n = double(g.nees_steps);
		g.nees = neesSum / n;
		g.nees_lower = chi2Quantile(0.025, 3 * n) / n;
		g.nees_upper = chi2Quantile(0.975, 3 * n) / n;
	}
	return g;
}
}  // namespace dynslam::eval
