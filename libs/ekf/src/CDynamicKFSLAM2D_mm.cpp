/** CDynamicKFSLAM2D: multiple-model objects (object_model = mm, issue 28; doc/state-layout.md
 * "Multiple-model objects"): per object, the modes' predictions of [pose; velocity] mixed by
 * their probabilities (models/mode_mixture.h), which this step's readings of the object update
 * first (a GPB1-style switch). The update that follows is objectFeatureUpdates(), as for cv. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <map>
#include <stdexcept>
#include <string>

#include "object_sighting.h"

namespace dynslam
{
using estimator::BlockKind;

std::vector<std::string> CDynamicKFSLAM2D::objectModeNames() const
{
	return estimator::modeNames(*m_motion);
}

void CDynamicKFSLAM2D::predictObjectModes(int32_t obj, const std::vector<int>& idx)
{
	auto x = m_xkk.asEigen();
	auto P = cov();
	const models::TModeMixture mix = m_modes.predict(
	    *m_motion, obj, m_step, x(idx), ekf::marginal(P, idx),
	    [&](const estimator::TModePredictions& pred) { return modeLogLikelihoods(obj, idx, pred); },
	    m_drop.record());
	ekf::predictSubset(x, P, idx, mix.s, mix.F, mix.Q_eff);
}

Eigen::VectorXd CDynamicKFSLAM2D::modeLogLikelihoods(int32_t obj, const std::vector<int>& idx,
                                                     const estimator::TModePredictions& pred) const
{
	std::vector<estimator::TRoutedReading> readings;  // copies: with() returns a temporary
	for (const auto& m : m_routed.with(estimator::Route::ObjectTimeT))
		if (m.object == obj) readings.push_back(m);
	if (readings.empty()) return Eigen::VectorXd();
	// The entries the readings depend on: ego, [pose; velocity] (idx), the features' f_0.
	const estimator::TObjectEntry& info = m_router->registry().at(obj);
	std::vector<int> all = {0, 1, 2};
	all.insert(all.end(), idx.begin(), idx.end());
	const Eigen::Index n = Eigen::Index(info.feature_ids.size());
	std::map<int32_t, size_t> f0Block;  // one scan of the layout
	for (size_t b = 0; b < m_layout.size(); ++b)
		if (m_layout[b].kind == BlockKind::ObjectFeature0)  // by ID, as objectFeatureUpdates
			f0Block[m_layout[b].id] = b;
	for (const int32_t id : info.feature_ids)
	{
		const auto f = f0Block.find(id);
		if (f == f0Block.end())
			throw std::logic_error("CDynamicKFSLAM2D (mm): a feature of object " +
			                       std::to_string(obj) + " has no f_0");
		const std::vector<int> fi = m_layout.indices(f->second);
		all.insert(all.end(), fi.begin(), fi.end());
	}
	const auto x = m_xkk.asEigen();
	const Eigen::MatrixXd P_all = ekf::marginal(cov(), all);
	const Eigen::Index ns = Eigen::Index(idx.size()), d = ns / 2;
	Eigen::Matrix2Xd f0(2, n);
	for (Eigen::Index k = 0; k < n; ++k) f0.col(k) = x.segment(all[size_t(3 + ns + 2 * k)], 2);
	const Eigen::Vector3d ego = x.head<3>();
	return estimator::readingsModeLogLikelihoods(
	    pred, P_all, d, Eigen::Index(readings.size()), options.Sigma_v,
	    [&](Eigen::Index r, const Eigen::VectorXd& xi)
	    {
		    estimator::TReadingSighting s;
		    const auto& z = readings[size_t(r)].reading;
		    const Eigen::Vector2d zhat =
		        detail::sighting(options.measurement_model, ego, m_in.sensor_pose, xi, f0,
		                         info.indexOf(z.id), &s.H_x, &s.H_xi, &s.H_f0, info.founders);
		    s.nu = models::innovation(options.measurement_model, z.z, zhat);
		    return s;
	    });
}

void CDynamicKFSLAM2D::attachModeProbabilities(std::map<int32_t, TObjectTrack>& tracks) const
{
	for (auto& [obj, track] : tracks)
		for (TObjectPoseEstimate& e : track.poses)
			if (const Eigen::VectorXd* mu = m_modes.at(obj, e.step)) e.mode_probabilities = *mu;
}
}  // namespace dynslam
