/** The object-centric motion models' module (object_motion.h), AfterStaticUpdate: the sightings of
 * features of objects with a velocity as measurement updates of ego, object pose and body-frame
 * features (doc/state-layout.md "Object-centric motion models"). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/se2.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "object_motion.h"
#include "object_sighting.h"

namespace dynslam::ekf
{
using estimator::BlockKind;

namespace
{
/** The used readings of an object stacked into one update: H, nu and R = blockdiag(Sigma_v +
 * cth h h^T), h = the reading's column on the ego heading (H's column 2), cth = c P_thth
 * (cv_heading_inflation; 0: R = blockdiag(Sigma_v), today's update). The reading gate of
 * objectFeatureUpdates keeps Sigma_v: it tests the honest innovation covariance, the inflation
 * is not the reading's noise (doc/state-layout.md "Heading inflation of object readings"). */
void stackObjectReadings(const std::vector<Eigen::MatrixXd>& Hs,
                         const std::vector<Eigen::Vector2d>& nus, const Eigen::Matrix2d& Sigma_v,
                         double cth, Eigen::MatrixXd& H, Eigen::VectorXd& nu, Eigen::MatrixXd& R)
{
	const Eigen::Index m = Eigen::Index(Hs.size());
	H.resize(2 * m, Hs.front().cols());
	nu.resize(2 * m);
	R = Eigen::MatrixXd::Zero(2 * m, 2 * m);
	for (Eigen::Index r = 0; r < m; ++r)
	{
		H.middleRows(2 * r, 2) = Hs[size_t(r)];
		nu.segment(2 * r, 2) = nus[size_t(r)];
		R.block(2 * r, 2 * r, 2, 2) = Sigma_v;
		const Eigen::Vector2d h = Hs[size_t(r)].col(2);  // d z / d ego heading
		if (cth > 0) R.block(2 * r, 2 * r, 2, 2) += cth * h * h.transpose();
	}
}
}  // namespace

void CObjectMotionModule::objectFeatureUpdates(TFilterAccess& a)
{
	const estimator::CPaddedLayout& layout = a.layout();
	const std::map<int32_t, TObjectState> states = objectStates(layout);
	std::map<int32_t, std::vector<estimator::TRoutedReading>> byObject;
	for (const auto& m : a.routed().with(estimator::Route::ObjectTimeT))
	{
		const auto it = states.find(m.object);
		if (it != states.end() && it->second.velocity != SIZE_MAX) byObject[m.object].push_back(m);
	}
	if (byObject.empty()) return;
	// f0 blocks by feature ID
	std::map<int32_t, size_t> f0Block;
	for (size_t b = 0; b < layout.size(); ++b)
		if (layout[b].kind == BlockKind::ObjectFeature0) f0Block[layout[b].id] = b;
	const TModelOptions& options = a.options();
	auto x = a.mean();
	auto P = a.cov();
	const double gate = a.motion().readingGate();
	for (const auto& [obj, readings] : byObject)
	{
		const estimator::TObjectEntry& info = a.router().registry().at(obj);
		const int n = int(info.feature_ids.size());
		const std::vector<int> ip = layout.indices(states.at(obj).pose);
		std::vector<int> idx = concat({0, 1, 2}, ip);
		for (const int32_t id : info.feature_ids) idx = concat(idx, layout.indices(f0Block.at(id)));
		Eigen::Matrix2Xd f0(2, n);
		for (int k = 0; k < n; ++k) f0.col(k) = x.segment(idx[3 + ip.size() + 2 * k], 2);
		const Eigen::Vector3d ego = x.head<3>();
		const Eigen::VectorXd xi = x(ip);
		const Eigen::MatrixXd Pii = P(idx, idx);
		const int d = int(ip.size());
		std::vector<Eigen::MatrixXd> Hs;
		std::vector<Eigen::Vector2d> nus;
		for (const auto& m : readings)
		{
			models::Matrix23d J_z_x;
			Eigen::MatrixXd J_z_xi, J_z_f0;
			const Eigen::Vector2d zhat = detail::sighting(
			    options.measurement_model, ego, a.sensorPose(), xi, f0, info.indexOf(m.reading.id),
			    &J_z_x, &J_z_xi, &J_z_f0, info.founders);
			Eigen::MatrixXd H(2, idx.size());
			H << J_z_x, J_z_xi, J_z_f0;
			const Eigen::Vector2d nu =
			    models::innovation(options.measurement_model, m.reading.z, zhat);
			if (std::isfinite(gate))
			{
				const Eigen::Matrix2d S = H * Pii * H.transpose() + options.Sigma_v;
				const double nis = nu.dot(S.ldlt().solve(nu));
				if (nis > gate)
				{
					++a.report().object_gated_out;
					continue;
				}
			}
			Hs.push_back(H);
			nus.push_back(nu);
		}
		// Every reading gated out: the object coasts on its prediction; at the model's count of
		// such steps in a row it is lost (planFallbacks removes its motion state).
		if (a.motion().reportGating(obj, Hs.empty())) m_lostNow.insert(obj);
		if (Hs.empty()) continue;
		const Eigen::Index m = Eigen::Index(Hs.size());
		Eigen::MatrixXd H, R;
		Eigen::VectorXd nu;
		stackObjectReadings(Hs, nus, options.Sigma_v, options.cv.heading_inflation * P(2, 2), H, nu,
		                    R);
		ekf::sparseUpdate(x, P, idx, H, nu, R);
		if (d == 3) x[ip[2]] = models::wrapToPi(x[ip[2]]);
		a.normalize();
		a.report().object_feature_updates += size_t(m);
	}
}
}  // namespace dynslam::ekf
