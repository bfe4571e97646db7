#include <dynslam/core/models/se2.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/eval/motion_metrics.h>

#include <cmath>
#include <map>
#include <set>

namespace dynslam::eval
{
namespace
{
using models::composePose;
using models::poseDifference;

struct TAcc
{
	std::vector<double> t, r;
	TMotionError finish() const
	{
		TMotionError m;
		m.n = t.size();
		m.n_rot = r.size();
		auto stats = [](const std::vector<double>& v, double& rmse, double& mean)
		{
			if (v.empty()) return;
			double s = 0, s2 = 0;
			for (double x : v)
			{
				s += x;
				s2 += x * x;
			}
			mean = s / double(v.size());
			rmse = std::sqrt(s2 / double(v.size()));
		};
		stats(t, m.trans_rmse, m.trans_mean);
		stats(r, m.rot_rmse, m.rot_mean);
		return m;
	}
};

bool finite(const Eigen::VectorXd& v) { return v.allFinite(); }
}  // namespace

Eigen::Vector3d bodyFrameMotion(const Eigen::Vector3d& xi_prev, const Eigen::Vector3d& xi_now,
                                const Eigen::Vector2d& c0)
{
	const Eigen::Vector3d Lp(c0.x() + xi_prev.x(), c0.y() + xi_prev.y(), xi_prev.z());
	const Eigen::Vector3d Ln(c0.x() + xi_now.x(), c0.y() + xi_now.y(), xi_now.z());
	return poseDifference(Ln, Lp);
}

TRelativePoseError relativePoseError(const io::TGroundTruth& gt,
                                     const std::vector<TEgoEstimate>& ego, int delta)
{
	TRelativePoseError r;
	r.delta = delta;
	std::map<int, Eigen::Vector3d> est;
	for (const auto& e : ego)
		if (e.step >= 0 && size_t(e.step) < gt.numSteps()) est[e.step] = e.mean;
	double st = 0, sr = 0;
	for (const auto& [k, a] : est)
	{
		const auto it = est.find(k + delta);
		if (delta <= 0 || it == est.end()) continue;
		const Eigen::Vector3d dEst = poseDifference(it->second, a);
		const Eigen::Vector3d dGt = poseDifference(gt.ego[size_t(k + delta)], gt.ego[size_t(k)]);
		const Eigen::Vector3d E = poseDifference(dEst, dGt);
		st += E.head<2>().squaredNorm();
		sr += E.z() * E.z();
		++r.n;
	}
	if (r.n)
	{
		r.trans_rmse = std::sqrt(st / double(r.n));
		r.rot_rmse = std::sqrt(sr / double(r.n));
	}
	return r;
}

TObjectErrors objectErrors(const io::TGroundTruth& gt, const TRunEstimates& est)
{
	// rotation centres: estimated f_0 centroid and the truth's centroid of the same features
	std::map<int32_t, std::pair<Eigen::Vector2d, Eigen::Vector2d>> c0;
	std::map<int32_t, std::vector<const TObjectFeatureEstimate*>> feats;
	for (const auto& f : est.object_features) feats[f.object].push_back(&f);
	for (const auto& [obj, fs] : feats)
	{
		if (obj < 0 || size_t(obj) >= gt.objects.size()) continue;
		const auto& o = gt.objects[size_t(obj)];
		if (o.first_step < 0) continue;
		Eigen::Vector2d ce = Eigen::Vector2d::Zero(), cg = Eigen::Vector2d::Zero();
		for (const auto* f : fs)
		{
			ce += f->mean;
			cg += o.features[size_t(o.first_step)].col(f->feature);
		}
		c0[obj] = {ce / double(fs.size()), cg / double(fs.size())};
	}
	std::map<int32_t, std::map<int, Eigen::Vector3d>> poses;  // object -> step -> xi (3-dof)
	std::map<int32_t, bool> rotates;
	for (const auto& p : est.object_poses)
	{
		if (!c0.count(p.object) || p.step < 0 || size_t(p.step) >= gt.numSteps()) continue;
		if (!finite(gt.objects[size_t(p.object)].pose[size_t(p.step)].head(p.mean.size())))
			continue;
		poses[p.object][p.step] = p.mean.size() == 3 ? Eigen::Vector3d(p.mean)
		                                             : Eigen::Vector3d(p.mean.x(), p.mean.y(), 0);
		rotates[p.object] = p.mean.size() == 3;
	}
	TObjectErrors out;
	TAcc all;
	std::vector<double> posAll;
	for (const auto& [obj, byStep] : poses)
	{
		const auto& [ce, cg] = c0.at(obj);
		const auto& truth = gt.objects[size_t(obj)].pose;
		TAcc acc;
		std::vector<double> pos;
		for (const auto& [k, xi] : byStep)
		{
			Eigen::Vector3d xg = truth[size_t(k)];
			if (!rotates[obj]) xg.z() = 0;
			pos.push_back(((ce + xi.head<2>()) - (cg + xg.head<2>())).norm());
			const auto prev = byStep.find(k - 1);
			if (prev == byStep.end()) continue;
			Eigen::Vector3d xgp = truth[size_t(k - 1)];
			if (!rotates[obj]) xgp.z() = 0;
			const Eigen::Vector3d E =
			    poseDifference(bodyFrameMotion(prev->second, xi, ce), bodyFrameMotion(xgp, xg, cg));
			acc.t.push_back(E.head<2>().norm());
			if (rotates[obj]) acc.r.push_back(std::abs(E.z()));
		}
		out.motion_per_object[obj] = acc.finish();
		out.position_rmse_per_object[obj] = rmse(pos);
		all.t.insert(all.t.end(), acc.t.begin(), acc.t.end());
		all.r.insert(all.r.end(), acc.r.begin(), acc.r.end());
		posAll.insert(posAll.end(), pos.begin(), pos.end());
	}
	out.motion = all.finish();
	out.position_n = posAll.size();
	out.position_rmse = rmse(posAll);
	return out;
}
}  // namespace dynslam::eval
