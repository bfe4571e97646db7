/** CWindowBackend: result getters (estimates and marginal covariances). */
#include <dynslam/common/backend_results.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/framework/CWindowBackend.h>

#include <algorithm>

namespace dynslam::framework
{
// ------------------------------------------------------------------------------------------
mrpt::poses::CPosePDFGaussian CWindowBackend::getEgoPose() const
{
	const TVarKey k = TVarKey::ego(m_step);
	mrpt::poses::CPosePDFGaussian p;
	if (m_step < 0) return p;
	const Eigen::Vector3d x = m_cost.value(k);
	p.mean = mrpt::poses::CPose2D(x[0], x[1], x[2]);
	p.cov = mrpt::math::CMatrixDouble33(Eigen::Matrix3d(m_cost.covariance({k}, gnOptions())));
	return p;
}

std::vector<TStaticLandmarkEstimate> CWindowBackend::getStaticLandmarks() const
{
	std::vector<TStaticLandmarkEstimate> out;
	std::vector<TVarKey> keys;
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::StaticLandmark) keys.push_back(k);
	if (!keys.empty())
	{
		const Eigen::MatrixXd C = m_cost.covariance(keys, gnOptions());
		for (size_t i = 0; i < keys.size(); ++i)
		{
			TStaticLandmarkEstimate e;
			e.id = keys[i].id;
			e.mean = m_cost.value(keys[i]);
			e.cov = C.block<2, 2>(2 * i, 2 * i);
			out.push_back(e);
		}
	}
	return out;
}

std::vector<TStaticLandmarkEstimate> CWindowBackend::getDroppedStaticLandmarks() const
{
	return m_droppedStatic;
}

std::vector<TObjectFeatureEstimate> CWindowBackend::getObjectFeatures() const
{
	std::vector<TObjectFeatureEstimate> out;
	const CRunningCost& c = objectCost();
	if (cube())
	{
		// f_0 = O_0 (+) (body_k - c0), the time-0 features implied by the body model.
		for (const auto& [obj, o] : m_router->registry().objects())
		{
			const TVarKey k0 = TVarKey::objectBodyPose(obj, o.first_step);
			if (!c.has(k0)) continue;
			const Eigen::VectorXd O = c.value(k0);
			const Eigen::MatrixXd C = c.covariance({k0}, gnOptions());
			const Eigen::Matrix2Xd& body = m_body.at(obj);
			const Eigen::Vector2d c0 = body.rowwise().mean();
			for (size_t j = 0; j < o.feature_ids.size(); ++j)
			{
				const Eigen::Vector2d mb = body.col(Eigen::Index(j)) - c0;
				TObjectFeatureEstimate e;
				e.object = obj;
				e.feature = o.feature_index[j];
				e.id = o.feature_ids[j];
				e.at_time0 = true;
				e.step = o.first_step;
				const double th = O.size() == 3 ? O[2] : 0.0;
				e.mean = O.head<2>() + models::rot2(th) * mb;
				Eigen::MatrixXd J = Eigen::MatrixXd::Identity(2, O.size());
				if (O.size() == 3) J.col(2) = models::rot2Derivative(th) * mb;
				e.cov = J * C * J.transpose();
				out.push_back(e);
			}
		}
		return out;
	}
	std::vector<TVarKey> keys;
	for (const auto& k : c.keys())
		if (k.kind == VarKind::ObjectFeature) keys.push_back(k);
	if (keys.empty()) return out;
	const Eigen::MatrixXd C = c.covariance(keys, gnOptions());
	for (size_t i = 0; i < keys.size(); ++i)
	{
		const auto& k = keys[i];
		TObjectFeatureEstimate e;
		e.object = k.id;
		e.feature = k.feature;
		e.id = m_router->featureId(k.id, k.feature);
		e.at_time0 = !m_router->registry().isTimeT(k.id, k.step);
		e.step = k.step;
		e.mean = c.value(k);
		e.cov = C.block<2, 2>(2 * i, 2 * i);
		out.push_back(e);
	}
	return out;
}

std::map<int32_t, TObjectTrack> CWindowBackend::getObjectTracks() const
{
	std::map<int32_t, TObjectTrack> out = tracksFromRegistry(m_router->registry());
	const CRunningCost& c = objectCost();
	for (const auto& [obj, o] : m_router->registry().objects())
	{
		TObjectTrack& tr = out[obj];
		for (const auto& k : c.keys())
			if (k.id == obj && (cube() ? k.kind == VarKind::ObjectBodyPose && k.step != o.first_step
			                           : k.kind == VarKind::ObjectPose))
				tr.poses.push_back(poseEstimate(obj, k.step));
	}
	sortTrackPoses(out);
	return out;
}
}  // namespace dynslam::framework
