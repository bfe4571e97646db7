/** Results: the whole state without pads, its labels, the gauge's Jacobian and the reported
 * covariance (reader.h). */
#include <dynslam/core/ekf_steps.h>

#include <string>

#include "../gauge/prior_gauge.h"
#include "reader.h"

namespace dynslam::ekf::results
{
using estimator::BlockKind;
using estimator::TBlock;

namespace
{
void appendLabels(const TBlock& t, std::vector<std::string>& labels)
{
	const std::string o = "obj" + std::to_string(t.object);
	switch (t.kind)
	{
		case BlockKind::StaticLandmark:
			labels.push_back("lm" + std::to_string(t.id) + ".x");
			labels.push_back("lm" + std::to_string(t.id) + ".y");
			break;
		case BlockKind::ObjectFeature0:
		case BlockKind::ObjectFeatureT:
		{
			const bool t0 = t.kind == BlockKind::ObjectFeature0;
			const std::string f =
			    o + ".f" + std::to_string(t.feature) + (t0 ? ".t0" : ".t" + std::to_string(t.step));
			labels.push_back(f + ".x");
			labels.push_back(f + ".y");
			break;
		}
		case BlockKind::ObjectPose:
		{
			const std::string p = o + ".xi" + std::to_string(t.step);
			labels.push_back(p + ".dx");
			labels.push_back(p + ".dy");
			if (t.dim == 3) labels.push_back(p + ".dtheta");
			break;
		}
		case BlockKind::ObjectVelocity:
			for (int i = 0; i < t.dim; ++i)
				labels.push_back(o + ".v" + std::to_string(t.step) + "." + std::to_string(i));
			break;
		case BlockKind::OdometryBias:
			labels.push_back("odo.b_w");
			if (t.dim == 2) labels.push_back("odo.s");
			break;
		case BlockKind::Compressed:  // never seen by a getter (the whole state is expanded)
			labels.push_back("c" + std::to_string(t.object) + "." + std::to_string(t.feature) +
			                 ".0");
			labels.push_back("c" + std::to_string(t.object) + "." + std::to_string(t.feature) +
			                 ".1");
			break;
	}
}
}  // namespace

void stateWithoutPads(const TFilterView& v, Eigen::VectorXd& x, Eigen::MatrixXd& P,
                      std::vector<std::string>* labels)
{
	const TFilterView::TStateRef s = v.whole();
	const std::vector<int> keep = ekf::keptIndices(int(s.x.size()), s.layout.padIndices());
	x = s.x(keep);
	P = v.gauge().anchored() ? Eigen::MatrixXd(reportedCov(v)(keep, keep))
	                         : Eigen::MatrixXd(s.P(keep, keep));
	if (!labels) return;
	labels->assign({"ego.x", "ego.y", "ego.theta"});
	for (const TBlock& t : s.layout.blocks()) appendLabels(t, *labels);
}

std::vector<size_t> padIndices(const TFilterView& v)
{
	const std::vector<int> p = v.whole().layout.padIndices();
	return std::vector<size_t>(p.begin(), p.end());
}

Eigen::MatrixXd gaugeJacobian(const TFilterView& v)
{
	const TFilterView::TStateRef s = v.whole();
	return v.gauge().jacobian(s.layout, s.x, v.motion());
}

Eigen::MatrixXd reportedCov(const TFilterView& v)
{
	const TFilterView::TStateRef s = v.whole();
	return v.gauge().reported(Eigen::MatrixXd(s.P), s.layout, s.x, v.motion());
}
}  // namespace dynslam::ekf::results
