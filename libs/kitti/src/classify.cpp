#include <dynslam/kitti/classify.h>

#include <algorithm>

namespace dynslam::kitti
{
double footprintRadius(const std::vector<Eigen::Vector2d>& centres)
{
	if (centres.size() < 2) return 0;
	Eigen::Vector2d mean = Eigen::Vector2d::Zero();
	for (const auto& c : centres) mean += c;
	mean /= double(centres.size());
	double r = 0;
	for (const auto& c : centres) r = std::max(r, (c - mean).norm());
	return r;
}
}  // namespace dynslam::kitti
