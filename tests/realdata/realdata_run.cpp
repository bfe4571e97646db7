#include "realdata_run.h"

#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/eval/consistency.h>

#include <cmath>
#include <stdexcept>

namespace dynslam::realdata
{
namespace
{
const io::TObjectGroundTruth* findObject(const io::TGroundTruth& gt, int object)
{
	for (const auto& o : gt.objects)
		if (o.object == object) return &o;
	return nullptr;
}

/** Online positions p_k = f_0 + xi_k of every object whose pose at step k is in the state. */
void recordTracked(const CDynamicKFSLAM2D& f, const io::TGroundTruth& gt, int k,
                   std::vector<TTrackedPosition>& out)
{
	const auto& slots = f.getSlots();
	const auto& x = f.fullMean();
	const auto& P = f.fullCov();
	std::map<int, size_t> f0, pose;  // object -> slot
	for (size_t s = 0; s < slots.size(); ++s)
	{
		if (slots[s].kind == SlotKind::ObjectFeature0 && slots[s].feature == 0)
			f0[slots[s].object] = s;
		if (slots[s].kind == SlotKind::ObjectPoseA && slots[s].step == k) pose[slots[s].object] = s;
	}
	for (const auto& [obj, sp] : pose)
	{
		const auto it = f0.find(obj);
		const io::TObjectGroundTruth* o = findObject(gt, obj);
		if (it == f0.end() || !o || o->num_features != 1 || size_t(k) >= o->features.size())
			continue;
		// translation-only poses only (a rigid pose would need the rotation about the centroid)
		if (sp + 1 < slots.size() && slots[sp + 1].kind == SlotKind::ObjectPoseB) continue;
		const Eigen::Vector2d truth = o->features[size_t(k)].col(0);
		if (!truth.allFinite()) continue;
		const size_t a = 3 + 2 * it->second, b = 3 + 2 * sp;
		TTrackedPosition p;
		p.object = obj;
		p.step = k;
		p.truth = truth;
		p.est = Eigen::Vector2d(x[a] + x[b], x[a + 1] + x[b + 1]);
		for (int i = 0; i < 2; ++i)
			for (int j = 0; j < 2; ++j)
				p.cov(i, j) = P(a + i, a + j) + P(b + i, b + j) + P(a + i, b + j) + P(b + i, a + j);
		const auto m = eval::mahalanobis2(p.est - p.truth, p.cov);
		p.nees = m ? *m : std::nan("");
		out.push_back(p);
	}
}
}  // namespace

TTrackedSummary summarizeTracked(const std::vector<TTrackedPosition>& v, int object)
{
	TTrackedSummary s;
	s.object = object;
	double se = 0, nees = 0;
	size_t nn = 0, in95 = 0;
	for (const auto& p : v)
	{
		if (object >= 0 && p.object != object) continue;
		se += (p.est - p.truth).squaredNorm();
		++s.n;
		if (std::isfinite(p.nees))
		{
			nees += p.nees;
			++nn;
			if (p.nees < 5.991464547) ++in95;
		}
	}
	s.rmse = s.n ? std::sqrt(se / double(s.n)) : std::nan("");
	s.mean_nees = nn ? nees / double(nn) : std::nan("");
	s.frac_nees_in95 = nn ? double(in95) / double(nn) : std::nan("");
	return s;
}

TRealDataResult runRealData(const apps::TRawlog& rawlog, const io::TGroundTruth& gt,
                            const mrpt::config::CConfigFileMemory& ini, const std::string& filter)
{
	mrpt::config::CConfigFileMemory params(ini.getContent());
	std::string kind = filter;
	if (filter == "dynamic" || filter == "dynamic_nogate") kind = "ekf";
	if (filter == "dynamic_nogate")
	{
		// no outlier handling at all, whatever the INI's outlier_method
		params.write("DynamicKFSLAM", "innovation_gate", 0);
		params.write("DynamicKFSLAM", "outlier_method", "none");
	}
	auto backend = apps::makeBackend(kind, params);
	const auto* dyn = dynamic_cast<const CDynamicKFSLAM2D*>(backend.get());

	TRealDataResult r;
	r.filter = filter;
	auto perStep = [&](size_t done, size_t)
	{
		const TStepReport& rep = backend->getLastStepReport();
		r.gated_out += rep.gated_out;
		r.static_updates += rep.static_updates;
		if (dyn) recordTracked(*dyn, gt, int(done) - 1, r.tracked);
	};
	r.run = apps::runFilter(*backend, rawlog.actions, rawlog.frames, perStep);
	r.run.name = filter;
	r.eval = apps::evaluateRun(gt, r.run.est);
	r.ate = r.eval.metrics.ate;
	const auto& sm = r.eval.metrics.static_map;
	r.landmark_rmse = std::sqrt(sm.x * sm.x + sm.y * sm.y);
	r.landmarks_scored = sm.n_xy;

	for (const auto& p : r.tracked)
		if (!r.tracked_by_robot.count(p.object))
			r.tracked_by_robot[p.object] = summarizeTracked(r.tracked, p.object);
	r.tracked_all = summarizeTracked(r.tracked, -1);
	return r;
}
}  // namespace dynslam::realdata
