#include <dynslam/core/models/object_pose.h>
#include <dynslam/framework/object_pose_step.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace dynslam::framework
{
PoseStep addObjectPose(CRunningCost& c, int32_t obj, int first_step,
                       const std::vector<int32_t>& features, const std::vector<TVarKey>& newT,
                       int step, bool poseSpace, const Eigen::Matrix2d& Sigma_xi,
                       TObjectPoseKeys& k)
{
	k = TObjectPoseKeys();
	for (const auto& key : newT)
		if (key.id == obj)
		{
			k.ft.push_back(key);
			k.seen.push_back(
			    int(std::find(features.begin(), features.end(), key.feature) - features.begin()));
		}
	const size_t n = features.size(), m = k.ft.size();
	if (m == 0) return PoseStep::NotSeen;
	if (n >= 2 && m < 2) return PoseStep::Degenerate;
	Eigen::Matrix2Xd f0(2, n), ft(2, m);
	for (size_t j = 0; j < n; ++j)
	{
		k.f0.push_back(TVarKey::objectFeature(obj, features[j], first_step));
		f0.col(j) = c.value(k.f0.back());
	}
	for (size_t i = 0; i < m; ++i) ft.col(i) = c.value(k.ft[i]);
	Eigen::VectorXd xi;
	try
	{
		xi = n == 1 ? Eigen::VectorXd(models::objectTranslationInverse(f0.col(0), ft.col(0)))
		            : Eigen::VectorXd(models::objectPoseInverse(f0, ft, k.seen));
	}
	catch (const std::domain_error&)
	{
		return PoseStep::Degenerate;
	}
	k.pose = TVarKey::objectPose(obj, step);
	c.addVariable(k.pose, xi);
	if (poseSpace)
		c.addTerm(std::make_shared<CObjectPosePoseTerm>(k, Sigma_xi));
	else
		c.addTerm(std::make_shared<CObjectPoseFeatureTerm>(k, Sigma_xi));
	return PoseStep::Added;
}
}  // namespace dynslam::framework
