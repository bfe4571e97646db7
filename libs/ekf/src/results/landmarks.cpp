/** Results: the ego pose, the static landmarks (live and dropped), the object features
 * (reader.h). */
#include "../gauge/prior_gauge.h"
#include "../modules/module_list.h"
#include "../modules/object_drop.h"
#include "reader.h"

namespace dynslam::ekf
{
using estimator::BlockKind;
using estimator::TBlock;

const std::vector<TObjectFeatureEstimate>* TFilterView::droppedObjectFeatures() const
{
	const CObjectDropModule* drops = f.m_modules->objectDrop();  // drop_object_after_unseen_steps
	return drops ? &drops->droppedFeatures() : nullptr;
}

namespace results
{
mrpt::poses::CPosePDFGaussian egoPose(const TFilterView& v)
{
	const TFilterView::TStateRef s = v.working();
	mrpt::poses::CPosePDFGaussian p;
	p.mean = mrpt::poses::CPose2D(s.x[0], s.x[1], s.x[2]);
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) p.cov(i, j) = s.P(i, j);
	if (!v.gauge().anchored()) return p;  // no output term: no allocation per call
	const Eigen::MatrixXd g = v.gauge().term(nullptr, s.x.head<3>());
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) p.cov(i, j) += g(i, j);
	return p;
}

std::vector<TStaticLandmarkEstimate> staticLandmarks(const TFilterView& v)
{
	const TFilterView::TStateRef s = v.whole();
	std::vector<TStaticLandmarkEstimate> out;
	for (size_t b = 0; b < s.layout.size(); ++b)
	{
		if (s.layout[b].kind != BlockKind::StaticLandmark) continue;
		const int k = s.layout.first(b);
		TStaticLandmarkEstimate e;
		e.id = s.layout[b].id;
		e.mean = s.x.segment<2>(k);
		e.cov = s.P.block<2, 2>(k, k);
		e.cov += v.gauge().term(&s.layout[b], e.mean);
		e.in_state = true;
		out.push_back(e);
	}
	return out;
}

std::vector<TStaticLandmarkEstimate> droppedStaticLandmarks(const TFilterView& v)
{
	std::vector<TStaticLandmarkEstimate> out;
	out.reserve(v.droppedStatic().size());
	const TBlock point;  // a static landmark: a world point
	for (TStaticLandmarkEstimate e : v.droppedStatic())
	{
		e.cov += v.gauge().term(&point, e.mean);
		out.push_back(e);
	}
	return out;
}

std::vector<TObjectFeatureEstimate> objectFeatures(const TFilterView& v)
{
	const TFilterView::TStateRef s = v.working();
	std::vector<TObjectFeatureEstimate> out;
	for (size_t b = 0; b < s.layout.size(); ++b)
	{
		const TBlock& t = s.layout[b];
		if (t.kind != BlockKind::ObjectFeature0 && t.kind != BlockKind::ObjectFeatureT) continue;
		const int k = s.layout.first(b);
		TObjectFeatureEstimate e;
		e.object = t.object;
		e.feature = t.feature;
		e.id = t.id;
		e.at_time0 = t.kind == BlockKind::ObjectFeature0;
		e.step = t.step;
		e.mean = Eigen::Vector2d(s.x[k], s.x[k + 1]);
		e.cov << s.P(k, k), s.P(k, k + 1), s.P(k + 1, k), s.P(k + 1, k + 1);
		e.cov += v.gauge().term(&t, e.mean);
		out.push_back(e);
	}
	TBlock f0;  // recorded f_0 of dropped objects: their relative covariance plus the gauge's
	f0.kind = BlockKind::ObjectFeature0;
	if (const std::vector<TObjectFeatureEstimate>* dropped = v.droppedObjectFeatures())
		for (TObjectFeatureEstimate e : *dropped)
		{
			e.cov += v.gauge().term(&f0, e.mean);
			out.push_back(e);
		}
	return out;
}
}  // namespace results
}  // namespace dynslam::ekf
