#include "kitti_run.h"

#include <dynslam/apps/CCompareApp.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <cmath>

namespace dynslam::kitti_eval
{
TKittiRunResult runKitti(const apps::TRawlog& rawlog, const io::TGroundTruth& gt,
                         const mrpt::config::CConfigFileMemory& ini, const std::string& filter,
                         const std::vector<io::TReadingClass>& classes)
{
	mrpt::config::CConfigFileMemory params(ini.getContent());
	const bool dyn = filter == "dynamic" || filter == "dynamic_nogate";
	if (filter == "dynamic_nogate") params.write("DynamicKFSLAM", "innovation_gate", 0);
	auto backend = apps::makeBackend(dyn ? "ekf" : filter, params);
	TKittiRunResult r;
	r.filter = filter;
	const auto* ekf = dynamic_cast<const CDynamicKFSLAM2D*>(backend.get());
	const bool classifies = ekf && ekf->options.feature_labels == "classify";
	apps::TClassDecisions decisions;
	auto perStep = [&](size_t, size_t)
	{
		const TStepReport& rep = backend->getLastStepReport();
		r.gated_out += rep.gated_out;
		r.static_updates += rep.static_updates;
		if (classifies) decisions.add(ekf->lastRoutedStep());
	};
	r.run = apps::runFilter(*backend, rawlog.actions, rawlog.frames, perStep);
	r.run.name = filter;
	r.eval = apps::evaluateRun(gt, r.run.est);
	r.ate = r.eval.metrics.ate;
	const auto& sm = r.eval.metrics.static_map;
	r.map_rmse = std::sqrt(sm.x * sm.x + sm.y * sm.y);
	r.landmarks_scored = sm.n_xy;
	r.rpe = eval::relativePoseError(gt, r.run.est.ego, 10);
	r.objects = eval::objectErrors(gt, r.run.est);
	r.velocity = eval::objectVelocityErrors(gt, r.run.est);
	eval::TRunEstimates seen = r.run.est;
	seen.object_poses.clear();
	for (const auto& p : r.run.est.object_poses)
		if (p.object >= 0 && size_t(p.object) < gt.objects.size() && p.step >= 0 &&
		    size_t(p.step) < gt.objects[size_t(p.object)].visible.size() &&
		    gt.objects[size_t(p.object)].visible[size_t(p.step)])
			seen.object_poses.push_back(p);
	r.objects_seen = eval::objectErrors(gt, seen);
	r.velocity_seen = eval::objectVelocityErrors(gt, seen);
	if (classifies && !classes.empty())
	{
		r.class_reading = eval::perReadingScores(classes, decisions.decisions);
		r.class_track = eval::perTrackScores(classes, decisions.decisions);
		r.group_ari = eval::groupingAri(classes, decisions.groups);
	}
	return r;
}
}  // namespace dynslam::kitti_eval

#include <dynslam/core/models/se2.h>
#include <mrpt/obs/CActionRobotMovement2D.h>

namespace dynslam::kitti_eval
{
TOdometryOnly deadReckoning(const apps::TRawlog& rawlog, const io::TGroundTruth& gt)
{
	std::vector<eval::TEgoEstimate> ego;
	Eigen::Vector3d x = Eigen::Vector3d::Zero();
	double se = 0;
	for (size_t k = 0; k < rawlog.size() && k < gt.numSteps(); ++k)
	{
		const auto mv = rawlog.actions[k]->getBestMovementEstimation();
		if (!mv)
			throw std::runtime_error("deadReckoning: step " + std::to_string(k) +
			                         " has no odometry");
		const auto m = mv->poseChange->getMeanVal();
		x = models::composePose(x, Eigen::Vector3d(m.x(), m.y(), m.phi()));
		eval::TEgoEstimate e;
		e.step = int(k);
		e.mean = x;
		ego.push_back(e);
		se += (x.head<2>() - gt.ego[k].head<2>()).squaredNorm();
	}
	TOdometryOnly r;
	r.ate = ego.empty() ? NAN : std::sqrt(se / double(ego.size()));
	r.rpe = eval::relativePoseError(gt, ego, 10);
	return r;
}
}  // namespace dynslam::kitti_eval
