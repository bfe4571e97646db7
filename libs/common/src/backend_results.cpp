#include <dynslam/common/backend_results.h>

#include <algorithm>
#include <stdexcept>
#include <string>

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

namespace
{
/** Packs a 2- or 3-vector and its covariance into the fixed-size fields of a record; returns
 * the dimension. Throws std::invalid_argument naming `who` for any other shape. */
int packFixed(const Eigen::VectorXd& v, const Eigen::MatrixXd& c, Eigen::Vector3d& outV,
              Eigen::Matrix3d& outC, const char* who)
{
	const auto d = v.size();
	if ((d != 2 && d != 3) || c.rows() != d || c.cols() != d)
		throw std::invalid_argument(std::string(who) +
		                            ": a pose or velocity has 2 or 3 entries and a matching "
		                            "covariance");
	outV.head(d) = v;
	outC.topLeftCorner(d, d) = c;
	return int(d);
}
}  // namespace

estimator::TPoseRecord toRecord(const TObjectPoseEstimate& e)
{
	estimator::TPoseRecord r;
	r.step = e.step;
	r.dim = packFixed(e.mean, e.cov, r.mean, r.cov, "toRecord");
	return r;
}

estimator::TVelocityRecord toVelocityRecord(const TObjectPoseEstimate& e)
{
	estimator::TVelocityRecord r;
	r.step = e.step;
	r.dim = packFixed(e.velocity, e.velocity_cov, r.velocity, r.cov, "toVelocityRecord");
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
		tr.skipped_late_readings = o.skipped_late_readings;
		tr.skipped_late_features = int(o.skipped_late_ids.size());
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
