#include <dynslam/core/models/se2.h>
#include <dynslam/eval/consistency.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/eval/velocity_metrics.h>

#include <cmath>

namespace dynslam::eval
{
namespace
{
bool finitePose(const io::TObjectGroundTruth& o, long k)
{
	return k >= 0 && size_t(k) < o.pose.size() && o.pose[size_t(k)].allFinite();
}
}  // namespace

std::optional<Eigen::Vector3d> trueObjectVelocity(const io::TObjectGroundTruth& o,
                                                  const std::vector<double>& t, int k)
{
	if (!finitePose(o, k) || size_t(k) >= t.size()) return std::nullopt;
	const long a = finitePose(o, long(k) - 1) ? k - 1 : k;
	const long b = finitePose(o, long(k) + 1) && size_t(k) + 1 < t.size() ? k + 1 : k;
	const double dt = t[size_t(b)] - t[size_t(a)];
	if (a == b || !(dt > 0)) return std::nullopt;
	Eigen::Vector3d d = o.pose[size_t(b)] - o.pose[size_t(a)];
	d[2] = models::wrapToPi(d[2]);
	return Eigen::Vector3d(d / dt);
}

std::optional<TVelocityErrors> objectVelocityErrors(const io::TGroundTruth& gt,
                                                    const TRunEstimates& est)
{
	std::map<int32_t, const io::TObjectGroundTruth*> truth;
	for (const auto& o : gt.objects) truth[o.object] = &o;
	TVelocityErrors out;
	std::vector<double> speed, omega;
	std::map<int32_t, std::vector<double>> perObject;
	double nees = 0;
	int dof = 0;
	bool any = false;
	for (const TObjectPoseEstimate& p : est.object_poses)
	{
		if (p.velocity.size() == 0) continue;
		any = true;
		const auto it = truth.find(p.object);
		const auto v =
		    it == truth.end() ? std::nullopt : trueObjectVelocity(*it->second, gt.t, p.step);
		if (!v)
		{
			++out.skipped;
			continue;
		}
		Eigen::VectorXd e = p.velocity - v->head(p.velocity.size());
		speed.push_back(e.head<2>().norm());
		perObject[p.object].push_back(speed.back());
		if (e.size() == 3) omega.push_back(e[2]);  // a rate: not wrapped
		++out.n;
		if (const auto m = mahalanobis2(e, p.velocity_cov))
		{
			nees += *m;
			dof += int(e.size());
		}
	}
	if (!any) return std::nullopt;
	out.n_omega = omega.size();
	out.speed_rmse = rmse(speed);
	out.omega_rmse = rmse(omega);
	out.anees = dof > 0 ? nees / dof : kNaN;
	for (const auto& [obj, errs] : perObject) out.speed_rmse_per_object[obj] = rmse(errs);
	return out;
}
}  // namespace dynslam::eval
