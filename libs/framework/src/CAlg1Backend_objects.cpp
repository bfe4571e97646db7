/** CAlg1Backend: the steps of the object-centric motion models (object_model = cv | ctrv,
 * issue 13) as framework operations: the prediction of each object's pose and velocity is a
 * motion term followed by a marginalization (as Alg. 7 for the ego, Theorem A.5), the
 * sightings of an object are measurement terms and one GN step (Theorem A.3), the velocity of
 * a new object is an augmentation (GN step on its initialisation term, Theorem A.1); with
 * object_model = mm the motion term is the modes' mixture (CObjectMixtureMotionTerm). The EKF's
 * counterparts are in libs/ekf/src/CDynamicKFSLAM2D_cv.cpp. */
#include <dynslam/common/backend_results.h>
#include <dynslam/common/seam_options.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/object_motion.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/framework/CAlg1Backend.h>
#include <dynslam/framework/object_motion_terms.h>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace dynslam::framework
{
std::shared_ptr<const estimator::IObjectMotionModel> CAlg1Backend::makeMotionModel(
    const TModelOptions& o)
{
	const estimator::TObjectMotionParams params = objectMotionParams(o);
	if (!estimator::objectMotionModels().caps(o.object_model).framework)
		throw std::invalid_argument("[DynamicKFSLAM] object_model = " + o.object_model +
		                            ": not implemented in the framework");
	if (!estimator::objectMotionModels().caps(o.object_model).object_centric)
		return estimator::objectMotionModels().make(o.object_model, params);
	const estimator::TCvParams& p = params.cv;
	// The EKF-only cv keys: each names what the framework does not implement.
	const std::pair<bool, const char*> ekfOnly[] = {
	    {p.fallback_steps > 0, "cv_fallback_steps: the fallback of a lost object"},
	    {p.heading_inflation > 0,
	     "cv_heading_inflation: the heading inflation of object readings"}};
	for (const auto& [set, what] : ekfOnly)
		if (set)
			throw std::invalid_argument(
			    std::string("[ObjectModel] ") + what +
			    " is not implemented in the framework (the dynamic EKF only)");
	auto model = estimator::objectMotionModels().make(o.object_model, params);
	// The model's process noise for a 3-dof pose (a 2-dof one uses its first two axes).
	Eigen::MatrixXd F, Q;
	model->predict(Eigen::VectorXd::Zero(3 + model->velocityDim(3)), &F, &Q);
	if ((Q.diagonal().array() <= 0).any())
		throw std::invalid_argument(
		    std::string("[ObjectModel] ") +
		    estimator::objectMotionModels().caps(o.object_model).noise_key +
		    ": every entry must be > 0 in the framework (its motion term needs an invertible "
		    "process noise; the dynamic EKF accepts 0)");
	return model;
}

bool CAlg1Backend::objectCentric() const { return m_motion->objectCentric(); }

std::vector<std::string> CAlg1Backend::objectModeNames() const
{
	return estimator::modeNames(*m_motion);
}

void CAlg1Backend::predictObjects(const estimator::TRoutedStep& in)
{
	if (!objectCentric()) return;
	for (auto& [obj, since] : m_velocitySince)
	{
		TVarKey xi, v = TVarKey::objectVelocity(obj, -1);
		for (const auto& k : m_cost.keys())
		{
			if (k.kind == VarKind::ObjectPose && k.id == obj) xi = k;  // one pose per object
			if (k.kind == VarKind::ObjectVelocity && k.id == obj) v = k;
		}
		if (xi.kind != VarKind::ObjectPose || !m_cost.has(v))
			throw std::logic_error("CAlg1Backend: an object velocity without its pose");
		// The pose of the previous step is replaced by the prediction: recorded like a drop.
		const int d = m_cost.dim(xi), dv = m_cost.dim(v);
		TObjectPoseEstimate e;
		e.step = xi.step;
		e.mean = m_cost.value(xi);
		e.cov = marginalCov(xi);
		// The velocity: the block's first d entries (ca: then its acceleration).
		e.velocity = m_cost.value(v).head(d);
		e.velocity_cov = marginalCov(v).topLeftCorner(d, d);
		m_router->registry().recordDroppedPose(obj, toRecord(e), m_drop.record());
		m_router->registry().recordDroppedVelocity(obj, toVelocityRecord(e), m_drop.record());
		Eigen::VectorXd s(d + dv);
		s << m_cost.value(xi), m_cost.value(v);
		const TVarKey xiNext = TVarKey::objectPose(obj, m_step);
		const TVarKey vNext = TVarKey::objectVelocity(obj, m_step);
		if (m_motion->modeCount() > 0)  // object_model = mm
		{
			const models::TModeMixture mix = m_modes.predict(
			    *m_motion, obj, m_step, s, m_cost.covariance({xi, v}),
			    [&](const estimator::TModePredictions& p)
			    { return modeLogLikelihoods(obj, xi, v, in, p); },
			    m_drop.record());
			m_cost.addVariable(xiNext, mix.s.head(d));
			m_cost.addVariable(vNext, mix.s.tail(dv));
			m_cost.addTerm(
			    std::make_shared<CObjectMixtureMotionTerm>(xi, v, xiNext, vNext, s, mix));
		}
		else
		{
			const Eigen::VectorXd pred = m_motion->predict(s, nullptr, nullptr);
			m_cost.addVariable(xiNext, pred.head(d));
			m_cost.addVariable(vNext, pred.tail(dv));
			m_cost.addTerm(std::make_shared<CObjectMotionTerm>(m_motion, xi, v, xiNext, vNext));
		}
		m_cost.marginalize({xi, v});
	}
	if (!m_modes.probabilities().empty())
	{
		std::set<int32_t> live;
		for (const auto& [obj, since] : m_velocitySince) live.insert(obj);
		m_modes.forget(live);
	}
}

Eigen::VectorXd CAlg1Backend::modeLogLikelihoods(int32_t obj, const TVarKey& xi, const TVarKey& v,
                                                 const estimator::TRoutedStep& in,
                                                 const estimator::TModePredictions& pred) const
{
	std::vector<estimator::TRoutedReading> readings;
	for (const auto& m : in.with(estimator::Route::ObjectTimeT))
		if (m.object == obj) readings.push_back(m);
	if (readings.empty()) return Eigen::VectorXd();
	if (m_anchorPending)
		throw std::logic_error("CAlg1Backend: object readings while the anchored ego is exact");
	// The entries the readings depend on: ego, [pose; velocity], the features' f_0.
	const estimator::TObjectEntry& info = m_router->registry().at(obj);
	std::vector<TVarKey> blocks{m_ego, xi, v};
	for (size_t j = 0; j < info.feature_ids.size(); ++j)
		blocks.push_back(TVarKey::objectFeature(obj, info.feature_index[j], info.first_step));
	const Eigen::MatrixXd P_e = m_cost.covariance(blocks);
	const Eigen::Index n = Eigen::Index(info.feature_ids.size());
	Eigen::Matrix2Xd f0(2, n);
	for (Eigen::Index k = 0; k < n; ++k) f0.col(k) = m_cost.value(blocks[size_t(3 + k)]);
	const Eigen::Vector3d ego = m_cost.value(m_ego);
	const auto& mo = m_opts.model;
	return estimator::readingsModeLogLikelihoods(
	    pred, P_e, m_cost.dim(xi), Eigen::Index(readings.size()), mo.Sigma_v,
	    [&](Eigen::Index r, const Eigen::VectorXd& pose)
	    {
		    estimator::TReadingSighting s;
		    const auto& z = readings[size_t(r)].reading;
		    const Eigen::Vector2d zhat = models::observeObjectFeatureFromSensor(
		        mo.measurement_model, ego, m_sensor, pose, f0, info.indexOf(z.id), &s.H_x, &s.H_xi,
		        &s.H_f0);
		    s.nu = models::innovation(mo.measurement_model, z.z, zhat);
		    return s;
	    });
}

void CAlg1Backend::objectFeatureUpdates(const estimator::TRoutedStep& in)
{
	std::map<int32_t, std::vector<estimator::TRoutedReading>> byObject;
	for (const auto& m : in.with(estimator::Route::ObjectTimeT))
		if (hasVelocity(m.object)) byObject[m.object].push_back(m);
	const auto& mo = m_opts.model;
	const double gate = m_motion->readingGate();
	for (const auto& [obj, readings] : byObject)
	{
		const estimator::TObjectEntry& info = m_router->registry().at(obj);
		TVarKey xi;
		for (const auto& k : m_cost.keys())
			if (k.kind == VarKind::ObjectPose && k.id == obj) xi = k;
		std::vector<TVarKey> f0;
		for (size_t j = 0; j < info.feature_ids.size(); ++j)
			f0.push_back(TVarKey::objectFeature(obj, info.feature_index[j], info.first_step));
		std::vector<CTermPtr> terms;
		for (const auto& m : readings)
			terms.push_back(std::make_shared<CObjectSightingTerm>(
			    m_ego.step, xi, f0, info.indexOf(m.reading.id), m.reading.z, mo.measurement_model,
			    mo.Sigma_v, m_sensor));
		if (std::isfinite(gate))  // each reading's NIS with its own innovation covariance
		{
			std::vector<TVarKey> blocks{m_ego, xi};
			blocks.insert(blocks.end(), f0.begin(), f0.end());
			const Eigen::MatrixXd P = m_cost.covariance(blocks);
			std::vector<Eigen::VectorXd> vals;
			for (const auto& k : blocks) vals.push_back(m_cost.value(k));
			std::vector<CTermPtr> kept;
			for (const auto& t : terms)
			{
				const TLinearization L = t->linearize(vals);
				Eigen::MatrixXd H(2, P.cols());
				for (size_t b = 0, c = 0; b < L.J.size(); c += size_t(L.J[b].cols()), ++b)
					H.middleCols(Eigen::Index(c), L.J[b].cols()) = L.J[b];
				const Eigen::Matrix2d S = H * P * H.transpose() + mo.Sigma_v;
				if (L.r.dot(S.ldlt().solve(L.r)) > gate)
					++m_report.object_gated_out;
				else
					kept.push_back(t);
			}
			terms = kept;
		}
		if (terms.empty()) continue;  // every reading gated out: the object coasts
		if (m_anchorPending)  // a velocity needs two sightings: after the first odometry noise
			throw std::logic_error("CAlg1Backend: object update while the anchored ego is exact");
		for (const auto& t : terms) m_cost.addTerm(t);
		gnAndCollapse();
		m_report.object_feature_updates += terms.size();
	}
}

void CAlg1Backend::initObjectVelocities()
{
	if (!objectCentric()) return;
	bool added = false;
	for (const auto& [obj, o] : m_router->registry().objects())
	{
		const TVarKey xi = TVarKey::objectPose(obj, m_step);
		if (hasVelocity(obj) || !m_cost.has(xi)) continue;
		const int d = m_cost.dim(xi);
		if (m_motion->velocityDim(d) == 0) continue;
		const int steps = m_step - o.first_step;
		const TVarKey v = TVarKey::objectVelocity(obj, m_step);
		m_cost.addVariable(v, m_motion->initialVelocity(m_cost.value(xi), steps, nullptr, nullptr));
		m_cost.addTerm(std::make_shared<CObjectVelocityInitTerm>(m_motion, xi, v, steps, d));
		m_velocitySince[obj] = m_step;
		added = true;
	}
	if (added) gnAndCollapse();
}
}  // namespace dynslam::framework
