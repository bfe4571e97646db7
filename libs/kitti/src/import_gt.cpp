#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/geometry.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "import_detail.h"

namespace dynslam::kitti::detail
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/** Footprint centre and yaw of a box in the world frame. */
Eigen::Vector3d worldBoxPose(const TKittiBox& b, const Eigen::Vector3d& ego)
{
	const Eigen::Vector2d c = egoToWorld(ego, boxCentreEgo(b));
	return {c.x(), c.y(), models::wrapToPi(ego.z() + boxYawEgo(b.ry))};
}

Eigen::Matrix<double, 2, 4> worldCorners(const TKittiBox& b, const Eigen::Vector3d& ego)
{
	Eigen::Matrix<double, 2, 4> w;
	const auto c = footprintCornersEgo(b);
	for (int j = 0; j < 4; ++j) w.col(j) = egoToWorld(ego, c.col(j));
	return w;
}

void addObject(const TTrack& t, const TKittiLabels& L, const std::vector<Eigen::Vector3d>& ego,
               const std::vector<uint8_t>& read, io::TGroundTruth& gt)
{
	const size_t n = ego.size();
	io::TObjectGroundTruth& o = gt.objects[size_t(t.object)];
	o.object = t.object;
	o.num_features = 4;
	o.first_step = t.first_read;
	o.features.assign(n, Eigen::Matrix2Xd::Constant(2, 4, kNaN));
	o.pose.assign(n, Eigen::Vector3d::Constant(kNaN));
	o.visible.assign(n, 0);
	Eigen::Vector3d p0 = Eigen::Vector3d::Constant(kNaN);
	for (size_t i : t.boxes)
		if (L.boxes[i].frame == t.first_read)
			p0 = worldBoxPose(L.boxes[i], ego[size_t(t.first_read)]);
	for (size_t i : t.boxes)
	{
		const TKittiBox& b = L.boxes[i];
		const size_t k = size_t(b.frame);
		o.features[k] = worldCorners(b, ego[k]);
		o.visible[k] = read[i];
		if (b.frame < t.first_read) continue;
		const Eigen::Vector3d p = worldBoxPose(b, ego[k]);
		o.pose[k] =
		    Eigen::Vector3d(p.x() - p0.x(), p.y() - p0.y(), models::wrapToPi(p.z() - p0.z()));
	}
}
struct TJitter
{
	size_t n = 0, nc = 0;
	double t2 = 0, r2 = 0, c2 = 0;
	double scale_num = 0, scale_den = 0;
};

/** The trajectory-scale diagnostic of TImportSummary (first and last frame of a static track). */
void addScale(const TTrack& t, const TKittiLabels& L, const std::vector<Eigen::Vector3d>& ego,
              TJitter& j)
{
	if (t.boxes.size() < 10) return;
	const TKittiBox& a = L.boxes[t.boxes.front()];
	const TKittiBox& b = L.boxes[t.boxes.back()];
	const Eigen::Vector3d& ea = ego[size_t(a.frame)];
	const Eigen::Vector3d& eb = ego[size_t(b.frame)];
	const Eigen::Vector2d d = eb.head<2>() - ea.head<2>();
	const Eigen::Vector2d q =
	    models::rot2(ea.z()) * boxCentreEgo(a) - models::rot2(eb.z()) * boxCentreEgo(b);
	j.scale_num += d.dot(q);
	j.scale_den += q.squaredNorm();
}

/** Static track: motions between consecutive read frames (truth: none) and corner scatter. */
void addJitter(const TTrack& t, const TKittiLabels& L, const std::vector<Eigen::Vector3d>& ego,
               const std::vector<uint8_t>& read, const Eigen::Matrix<double, 2, 4>& mean,
               TJitter& j)
{
	for (size_t a = 0; a < t.boxes.size(); ++a)
	{
		const size_t i = t.boxes[a];
		if (!read[i]) continue;
		const TKittiBox& b = L.boxes[i];
		const auto w = worldCorners(b, ego[size_t(b.frame)]);
		j.c2 += (w - mean).colwise().squaredNorm().sum();
		j.nc += 4;
		if (a == 0) continue;
		const size_t h = t.boxes[a - 1];
		if (!read[h] || L.boxes[h].frame + 1 != b.frame) continue;
		const Eigen::Vector3d M =
		    models::poseDifference(worldBoxPose(b, ego[size_t(b.frame)]),
		                           worldBoxPose(L.boxes[h], ego[size_t(L.boxes[h].frame)]));
		j.t2 += M.head<2>().squaredNorm();
		j.r2 += M.z() * M.z();
		++j.n;
	}
}
}  // namespace

void fillGroundTruth(const TKittiLabels& L, const std::vector<Eigen::Vector3d>& ego,
                     const std::vector<uint8_t>& read,
                     const std::map<std::pair<int, int>, int32_t>& ids, const TImportOptions& o,
                     TImportResult& res)
{
	io::TGroundTruth& gt = res.gt;
	gt.ego = ego;
	gt.t.clear();
	for (size_t k = 0; k < ego.size(); ++k) gt.t.push_back(double(k) * o.dt);
	size_t numObjects = 0;
	for (const auto& [id, t] : res.tracks)
		if (t.object >= 0) numObjects = std::max(numObjects, size_t(t.object) + 1);
	gt.objects.resize(numObjects);
	TJitter jit;
	for (const auto& [id, t] : res.tracks)
	{
		for (size_t i : t.boxes)
		{
			const TKittiBox& b = L.boxes[i];
			res.track_steps.push_back({b.frame, t.track, t.moving, read[i] != 0,
			                           worldBoxPose(b, ego[size_t(b.frame)]), b.l, b.w});
		}
		if (t.first_read < 0) continue;
		if (t.moving)
		{
			addObject(t, L, ego, read, gt);
			continue;
		}
		Eigen::Matrix<double, 2, 4> mean = Eigen::Matrix<double, 2, 4>::Zero();
		for (size_t i : t.boxes) mean += worldCorners(L.boxes[i], ego[size_t(L.boxes[i].frame)]);
		mean /= double(t.boxes.size());
		for (int c = 0; c < 4; ++c) gt.landmarks[ids.at({t.track, c})] = mean.col(c);
		addJitter(t, L, ego, read, mean, jit);
		addScale(t, L, ego, jit);
	}
	auto& s = res.summary;
	s.floor_n = jit.n;
	s.floor_trans_rmse = jit.n ? std::sqrt(jit.t2 / double(jit.n)) : 0;
	s.floor_rot_rmse = jit.n ? std::sqrt(jit.r2 / double(jit.n)) : 0;
	s.trajectory_scale = jit.scale_den > 0 ? jit.scale_num / jit.scale_den : kNaN;
	s.static_corner_rms = jit.nc ? std::sqrt(jit.c2 / double(jit.nc)) : 0;
	std::sort(res.track_steps.begin(), res.track_steps.end(),
	          [](const TTrackStepRow& a, const TTrackStepRow& b)
	          { return a.step != b.step ? a.step < b.step : a.track < b.track; });
	gt.checkConsistent();
}
}  // namespace dynslam::kitti::detail

namespace dynslam::kitti
{
std::vector<io::TReadingClass> readingClasses(const TImportResult& res)
{
	std::vector<io::TReadingClass> rows;
	rows.reserve(res.summary.readings);
	for (size_t k = 0; k < res.steps.size(); ++k)
	{
		const TStep& s = res.steps[k];
		for (size_t i = 0; i < s.readings.size(); ++i)
		{
			const TReading& r = s.readings[i];
			const TTrack& t = res.tracks.at(r.track);
			io::TReadingClass c;
			c.step = int(k);
			c.t = s.t;
			c.index = int(i);
			c.id = r.id;
			c.cls = t.moving ? io::TrueClass::Moving : io::TrueClass::Static;
			c.object = t.moving ? t.object : -1;
			c.true_id =
			    t.moving ? ids::objectFeatureId(t.object, r.corner) : 4 * t.track + r.corner;
			c.feature = t.moving ? r.corner : c.true_id;
			rows.push_back(c);
		}
	}
	return rows;
}
}  // namespace dynslam::kitti
