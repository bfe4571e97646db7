/** The router's context of CDynamicKFSLAM2D and its box tracks (router_context.h). */
#include "router_context.h"

#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/box_router.h>

namespace dynslam::ekf
{
estimator::TRouterContext routerContext(const TFilterView& v)
{
	const TModelOptions& o = v.options();
	const estimator::TStepInput& in = v.input();
	estimator::TRouterContext ctx;
	ctx.model = o.measurement_model;
	ctx.R = o.Sigma_v;
	ctx.sensor_pose = in.sensor_pose;
	ctx.u = in.u;
	ctx.U = o.motion_noise_from_action ? in.U : o.Sigma_w;
	ctx.static_innovation =
	    [v](int32_t id, const Eigen::Vector2d& z, estimator::TStaticInnovation& out)
	{ return staticInnovation(v, id, z, out); };
	ctx.boxes = &in.boxes;  // feature_labels = boxes
	ctx.ego = v.ego();
	ctx.stamp = in.stamp;
	ctx.box_prediction = [v](const std::array<int32_t, 4>& ids, Eigen::Vector2d& c,
	                         Eigen::Matrix2d& C) { return boxPrediction(v, ids, c, C); };
	return ctx;
}

bool staticInnovation(const TFilterView& v, int32_t id, const Eigen::Vector2d& z,
                      estimator::TStaticInnovation& out)
{
	const TModelOptions& o = v.options();
	const auto it = v.staticBlocks().find(id);
	// With the odometry bias the prediction also moves with the bias block: not modelled here.
	if (it == v.staticBlocks().end() || o.odometry_bias.enabled()) return false;
	const Eigen::Index k = v.layout().first(it->second);
	const auto P = v.cov();
	const auto m = v.mean();
	const Eigen::Vector3d x = v.ego();
	const Eigen::Vector2d f(m[k], m[k + 1]);
	// The ego predicted as propagateEgo() will (without first-estimate Jacobians).
	const estimator::TStepInput& in = v.input();
	Eigen::Matrix3d J_x_x, J_x_u;
	const bool skip = o.skip_prediction_on_empty_map && v.mapEmpty();
	const Eigen::Vector3d xp = skip ? x : models::composePose(x, in.u, &J_x_x, &J_x_u);
	if (skip) J_x_x.setIdentity(), J_x_u.setZero();
	const Eigen::Matrix3d& U = o.motion_noise_from_action ? in.U : o.Sigma_w;
	Eigen::Matrix<double, 5, 5> C;
	C.topLeftCorner<3, 3>() =
	    J_x_x * P.topLeftCorner(3, 3) * J_x_x.transpose() + J_x_u * U * J_x_u.transpose();
	C.topRightCorner<3, 2>() = J_x_x * P.block(0, k, 3, 2);
	C.bottomLeftCorner<2, 3>() = C.topRightCorner<3, 2>().transpose();
	C.bottomRightCorner<2, 2>() = P.block(k, k, 2, 2);
	models::Matrix23d J_z_x;
	Eigen::Matrix2d J_z_f;
	const Eigen::Vector2d zhat =
	    models::observeFromSensor(o.measurement_model, xp, in.sensor_pose, f, &J_z_x, &J_z_f);
	Eigen::Matrix<double, 2, 5> H;
	H << J_z_x, J_z_f;
	out.nu = models::innovation(o.measurement_model, z, zhat);
	out.S = H * C * H.transpose() + o.Sigma_v;
	out.J_z_f = J_z_f;
	return true;
}

bool boxPrediction(const TFilterView& v, const std::array<int32_t, 4>& ids, Eigen::Vector2d& c,
                   Eigen::Matrix2d& C)
{
	std::array<Eigen::Index, 4> k{};
	for (size_t i = 0; i < 4; ++i)
	{
		const auto it = v.staticBlocks().find(ids[i]);
		if (it == v.staticBlocks().end()) return false;
		k[i] = v.layout().first(it->second);
	}
	// The footprint centre is the mean of the four corners: c = A m, C = A P A^T with
	// A = [I/4 I/4 I/4 I/4] on the corners' blocks.
	const auto P = v.cov();
	const auto m = v.mean();
	c.setZero();
	C.setZero();
	for (size_t i = 0; i < 4; ++i)
	{
		c += 0.25 * Eigen::Vector2d(m[k[i]], m[k[i] + 1]);
		for (size_t j = 0; j < 4; ++j) C += P.block(k[i], k[j], 2, 2) / 16.0;
	}
	return true;
}

std::vector<TTrackedBox> trackedBoxes(const TFilterView& v)
{
	const estimator::IMeasurementRouter* router = v.router();
	const estimator::CBoxTracker* tracker = router ? router->boxTracker() : nullptr;
	if (!tracker) return {};
	const Eigen::Vector3d ego = v.ego();
	const Eigen::Vector3d placed = router->boxPlacementPose();
	std::vector<TTrackedBox> out;
	for (const estimator::TBoxTrack& t : tracker->tracks())
	{
		// tracker_baseline's output rule
		if (!v.options().boxes.reports(t, v.step() + 1)) continue;
		TTrackedBox b;
		b.track = t.id;
		b.cls = t.cls;
		b.score = t.score;
		// The tracker's box, relative to the pose that placed this step's boxes.
		b.pose = models::poseDifference(t.x.head<3>(), placed);
		// A box mapped as four static landmarks: the map's centre (after this step's update),
		// relative to the ego updated with it.
		Eigen::Vector2d c;
		Eigen::Matrix2d C;
		if (boxPrediction(v, estimator::CBoxRouter::cornerIds(t.id), c, C))
			b.pose = models::poseDifference(Eigen::Vector3d(c.x(), c.y(), t.x(2)), ego);
		b.extent = t.x.segment<2>(3);
		out.push_back(b);
	}
	return out;
}
}  // namespace dynslam::ekf
