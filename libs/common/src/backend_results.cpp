#include <dynslam/backend_results.h>

#include <algorithm>
#include <stdexcept>

namespace dynslam
{
TObjectPoseEstimate toEstimate(const estimator::TPoseRecord& r)
{
	TObjectPoseEstimate e;
	e.step = r.step;
	e.mean = r.mean.head(r.dim);
	e.cov = r.cov.topLeftCorner(r.dim, r.dim);
	e.in_state = false;
	return e;
}

estimator::TPoseRecord toRecord(const TObjectPoseEstimate& e)
{
	const auto d = e.mean.size();
	if ((d != 2 && d != 3) || e.cov.rows() != d || e.cov.cols() != d)
		throw std::invalid_argument(
		    "toRecord: a pose has 2 or 3 entries and a matching covariance");
	estimator::TPoseRecord r;
	r.step = e.step;
	r.dim = int(d);
	r.mean.head(d) = e.mean;
	r.cov.topLeftCorner(d, d) = e.cov;
	return r;
}

estimator::TVelocityRecord toVelocityRecord(const TObjectPoseEstimate& e)
{
	const auto d = e.velocity.size();
	if ((d != 2 && d != 3) || e.velocity_cov.rows() != d || e.velocity_cov.cols() != d)
		throw std::invalid_argument(
		    "toVelocityRecord: a velocity has 2 or 3 entries and a matching covariance");
	estimator::TVelocityRecord r;
	r.step = e.step;
	r.dim = int(d);
	r.velocity.head(d) = e.velocity;
	r.cov.topLeftCorner(d, d) = e.velocity_cov;
	return r;
}

std::map<int32_t, TObjectTrack> tracksFromRegistry(const estimator::CObjectRegistry& reg)
{
	std::map<int32_t, TObjectTrack> out;
	for (const auto& [obj, o] : reg.objects())
	{
		TObjectTrack& tr = out[obj];
		tr.object = obj;
		tr.first_step = o.first_step;
		tr.num_features = int(o.feature_ids.size());
		tr.poses.reserve(o.dropped_poses.size());
		for (const auto& r : o.dropped_poses) tr.poses.push_back(toEstimate(r));
		size_t i = 0;  // both ascending in step: attach each velocity to its pose
		for (const auto& v : o.dropped_velocities)
		{
			while (i < tr.poses.size() && tr.poses[i].step < v.step) ++i;
			if (i == tr.poses.size() || tr.poses[i].step != v.step) continue;  // pose not kept
			tr.poses[i].velocity = v.velocity.head(v.dim);
			tr.poses[i].velocity_cov = v.cov.topLeftCorner(v.dim, v.dim);
		}
	}
	return out;
}

void sortTrackPoses(std::map<int32_t, TObjectTrack>& tracks)
{
	for (auto& [obj, tr] : tracks)
		std::stable_sort(tr.poses.begin(), tr.poses.end(),
		                 [](const auto& a, const auto& b) { return a.step < b.step; });
}
}  // namespace dynslam
