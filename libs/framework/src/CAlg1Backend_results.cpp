/** CAlg1Backend: result getters, with the output term of prior_gauge = anchor. */
#include <dynslam/common/backend_results.h>
#include <dynslam/core/models/gauge.h>
#include <dynslam/framework/CAlg1Backend.h>

namespace dynslam::framework
{
namespace
{
/** How a variable transforms under the global rigid transform (models/gauge.h). */
models::GaugeKind gaugeKind(VarKind kind, int dim)
{
	switch (kind)
	{
		case VarKind::EgoPose:
			return models::GaugeKind::EgoPose;
		case VarKind::StaticLandmark:
		case VarKind::ObjectFeature:
			return models::GaugeKind::Point;
		case VarKind::ObjectPose:
		case VarKind::ObjectBodyPose:
			return dim == 3 ? models::GaugeKind::RelPose : models::GaugeKind::Vector;
		case VarKind::ObjectVelocity:
			return dim == 3 ? models::GaugeKind::Velocity3 : models::GaugeKind::Vector;
	}
	return models::GaugeKind::Invariant;
}
}  // namespace

Eigen::MatrixXd CAlg1Backend::gaugeTerm(VarKind kind, const Eigen::VectorXd& v) const
{
	if (!m_opts.model.prior_gauge_anchor) return Eigen::MatrixXd::Zero(v.size(), v.size());
	const Eigen::MatrixXd J = models::J_block_delta(gaugeKind(kind, int(v.size())), v,
	                                                m_opts.model.initial_pose.head<2>());
	return J * m_opts.model.Sigma_0 * J.transpose();
}

// ------------------------------------------------------------------------------------------
// Results
// ------------------------------------------------------------------------------------------
mrpt::poses::CPosePDFGaussian CAlg1Backend::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	const Eigen::Vector3d x = egoValue();
	p.mean = mrpt::poses::CPose2D(x[0], x[1], x[2]);
	const Eigen::Matrix3d P =
	    m_anchorPending ? Eigen::Matrix3d::Zero().eval() : Eigen::Matrix3d(marginalCov(m_ego));
	p.cov = mrpt::math::CMatrixDouble33(Eigen::Matrix3d(P + gaugeTerm(VarKind::EgoPose, x)));
	return p;
}

std::vector<TStaticLandmarkEstimate> CAlg1Backend::getStaticLandmarks() const
{
	std::vector<TStaticLandmarkEstimate> out;
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::StaticLandmark)
		{
			TStaticLandmarkEstimate e;
			e.id = k.id;
			e.mean = m_cost.value(k);
			e.cov = marginalCov(k) + gaugeTerm(k.kind, e.mean);
			out.push_back(e);
		}
	return out;
}

std::vector<TStaticLandmarkEstimate> CAlg1Backend::getDroppedStaticLandmarks() const
{
	std::vector<TStaticLandmarkEstimate> out;
	out.reserve(m_droppedStatic.size());
	for (TStaticLandmarkEstimate e : m_droppedStatic)
	{
		e.cov += gaugeTerm(VarKind::StaticLandmark, e.mean);
		out.push_back(e);
	}
	return out;
}

std::vector<TObjectFeatureEstimate> CAlg1Backend::getObjectFeatures() const
{
	std::vector<TObjectFeatureEstimate> out;
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::ObjectFeature)
		{
			TObjectFeatureEstimate e;
			e.object = k.id;
			e.feature = k.feature;
			e.id = m_router->featureId(k.id, k.feature);
			e.at_time0 = !isTimeT(k);
			e.step = k.step;
			e.mean = m_cost.value(k);
			e.cov = marginalCov(k) + gaugeTerm(k.kind, e.mean);
			out.push_back(e);
		}
	return out;
}

std::map<int32_t, TObjectTrack> CAlg1Backend::getObjectTracks() const
{
	std::map<int32_t, TObjectTrack> out = tracksFromRegistry(m_router->registry());
	for (auto& [obj, track] : out)  // dropped poses: recorded with the relative covariance
		for (TObjectPoseEstimate& e : track.poses)
		{
			e.cov += gaugeTerm(VarKind::ObjectPose, e.mean);
			if (e.velocity.size() > 0)
				e.velocity_cov += gaugeTerm(VarKind::ObjectVelocity, e.velocity);
		}
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::ObjectPose)
		{
			TObjectPoseEstimate e;
			e.step = k.step;
			e.mean = m_cost.value(k);
			e.cov = marginalCov(k) + gaugeTerm(k.kind, e.mean);
			if (const TVarKey v = TVarKey::objectVelocity(k.id, k.step); m_cost.has(v))
			{
				// The velocity: the block's first entries (ca: then its acceleration).
				const Eigen::Index d = e.mean.size();
				e.velocity = m_cost.value(v).head(d);
				e.velocity_cov = marginalCov(v).topLeftCorner(d, d) + gaugeTerm(v.kind, e.velocity);
			}
			e.in_state = true;
			out[k.id].poses.push_back(e);
		}
	sortTrackPoses(out);
	for (auto& [obj, track] : out)  // object_model = mm
		for (TObjectPoseEstimate& e : track.poses)
			if (const Eigen::VectorXd* mu = m_modes.at(obj, e.step)) e.mode_probabilities = *mu;
	return out;
}

void CAlg1Backend::getLabelledState(Eigen::VectorXd& x, Eigen::MatrixXd& P,
                                    std::vector<std::string>& labels) const
{
	TGaussNewtonOptions o;
	o.solver = SolverKind::Dense;
	// anchor, while the ego is exact: it is no variable of the cost; it comes first, covariance 0.
	std::vector<TVarKey> keys = m_cost.keys();
	const int e = m_anchorPending ? 3 : 0, n = m_cost.totalDim();
	x.resize(e + n);
	P = Eigen::MatrixXd::Zero(e + n, e + n);
	if (e) x.head(3) = m_fixedEgo;
	if (n)
	{
		x.tail(n) = m_cost.stackedValues();
		P.bottomRightCorner(n, n) = m_cost.covariance(keys, o);
	}
	if (e) keys.insert(keys.begin(), m_ego);
	if (m_opts.model.prior_gauge_anchor)  // + N Sigma_0 N^T
	{
		Eigen::MatrixXd N(x.size(), 3);
		for (size_t b = 0, i = 0; b < keys.size(); ++b)
		{
			const int d = keys[b] == m_ego ? 3 : m_cost.dim(keys[b]);
			N.middleRows(Eigen::Index(i), d) =
			    models::J_block_delta(gaugeKind(keys[b].kind, d), x.segment(Eigen::Index(i), d),
			                          m_opts.model.initial_pose.head<2>());
			i += size_t(d);
		}
		P = models::addGaugeTerm(P, N, m_opts.model.Sigma_0);
	}
	labels.clear();
	for (const auto& k : keys)
	{
		const std::string ob = "obj" + std::to_string(k.id);
		switch (k.kind)
		{
			case VarKind::EgoPose:
				labels.insert(labels.end(), {"ego.x", "ego.y", "ego.theta"});
				break;
			case VarKind::StaticLandmark:
				labels.push_back("lm" + std::to_string(k.id) + ".x");
				labels.push_back("lm" + std::to_string(k.id) + ".y");
				break;
			case VarKind::ObjectFeature:
			{
				const std::string f = ob + ".f" + std::to_string(k.feature) +
				                      (isTimeT(k) ? ".t" + std::to_string(k.step) : ".t0");
				labels.push_back(f + ".x");
				labels.push_back(f + ".y");
				break;
			}
			case VarKind::ObjectPose:
			case VarKind::ObjectBodyPose:
			{
				const std::string p = ob + ".xi" + std::to_string(k.step);
				labels.push_back(p + ".dx");
				labels.push_back(p + ".dy");
				if (m_cost.dim(k) == 3) labels.push_back(p + ".dtheta");
				break;
			}
			case VarKind::ObjectVelocity:  // the EKF's label: the step the velocity was added
				for (int i = 0; i < m_cost.dim(k); ++i)
					labels.push_back(ob + ".v" + std::to_string(m_velocitySince.at(k.id)) + "." +
					                 std::to_string(i));
				break;
		}
	}
}
}  // namespace dynslam::framework
