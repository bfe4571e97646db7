#pragma once
// Shared by the merge tests (test_object_merge_highway.cpp, test_object_merge_turning.cpp).
#include <dynslam/core/models/object_motion.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <optional>
#include <vector>

namespace dynslam_test
{
/** The world position of feature `id` of object obj: its pose map with its founders' centroid
 * (the documented meaning of xi), its newest pose; none while the object has no pose (e.g.
 * after a fallback, cv_fallback_steps). */
inline std::optional<Eigen::Vector2d> featureWorld(const dynslam::CDynamicKFSLAM2D& ekf,
                                                   int32_t obj, int32_t id)
{
	using dynslam::estimator::BlockKind;
	const dynslam::estimator::TObjectEntry& e = ekf.router().registry().at(obj);
	const auto& L = ekf.getLayout();
	const auto& x = ekf.fullMean();
	Eigen::VectorXd xi;
	int step = -1;
	Eigen::Matrix2Xd f0(2, e.feature_ids.size());
	for (size_t b = 0; b < L.size(); ++b)
	{
		if (L[b].object != obj) continue;
		const std::vector<int> idx = L.indices(b);
		if (L[b].kind == BlockKind::ObjectPose && L[b].step > step)
			xi = x.asEigen()(idx), step = L[b].step;
		if (L[b].kind == BlockKind::ObjectFeature0) f0.col(e.indexOf(L[b].id)) = x.asEigen()(idx);
	}
	if (xi.size() == 0) return std::nullopt;
	return dynslam::models::objectFeatureAt(xi, f0, e.indexOf(id), nullptr, nullptr,
	                                        e.founders < f0.cols() ? e.founders : 0);
}
}  // namespace dynslam_test
