#include <dynslam/kitti/detection_import.h>
#include <dynslam/kitti/geometry.h>

#include <stdexcept>
#include <string>

namespace dynslam::kitti
{
estimator::TBoxDetection egoBoxOfDetection(const TKittiDetection& d, int32_t group)
{
	estimator::TBoxDetection b;
	b.group = group;
	b.cls = d.type;
	b.score = d.score;
	const Eigen::Vector2d c = cameraToEgo(d.x, d.z);
	b.pose = Eigen::Vector3d(c.x(), c.y(), boxYawEgo(d.ry));
	b.extent = Eigen::Vector2d(d.l, d.w);
	return b;
}

void applyDetections(const std::vector<std::vector<TKittiDetection>>& kept, double max_range,
                     TImportResult& res, TDetectionSummary& summary)
{
	if (kept.size() > res.steps.size())
		throw std::invalid_argument("applyDetections: detections of " +
		                            std::to_string(kept.size()) + " frames for " +
		                            std::to_string(res.steps.size()) + " steps");
	res.detections = true;
	summary.written = summary.beyond_range = summary.frames_written = 0;
	int32_t group = 0;
	for (size_t k = 0; k < res.steps.size(); ++k)
	{
		TStep& s = res.steps[k];
		s.readings.clear();
		s.boxes.clear();
		if (k >= kept.size()) continue;
		for (const auto& d : kept[k])
		{
			estimator::TBoxDetection b = egoBoxOfDetection(d, group);
			if (b.pose.head<2>().norm() > max_range)
			{
				++summary.beyond_range;
				continue;
			}
			s.boxes.push_back(b);
			++group;
		}
		summary.written += s.boxes.size();
		summary.frames_written += !s.boxes.empty();
	}
}
}  // namespace dynslam::kitti
