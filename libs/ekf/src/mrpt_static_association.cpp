/** MRPT's data association for ID -1 readings (mrpt_static_association.h). */
#include <dynslam/ekf/mrpt_static_association.h>
#include <mrpt/slam/data_association.h>

#include <stdexcept>

namespace dynslam
{
namespace
{
mrpt::slam::TDataAssociationMetric metricOf(const std::string& m)
{
	if (m == "metricMaha") return mrpt::slam::metricMaha;
	if (m == "metricML") return mrpt::slam::metricML;
	throw std::invalid_argument("unknown data association metric '" + m + "'");
}
}  // namespace

estimator::StaticAssociationFn makeMrptStaticAssociation(const estimator::TUnknownIdParams& p)
{
	p.validate();
	const auto method = p.method == "assocJCBB" ? mrpt::slam::assocJCBB : mrpt::slam::assocNN;
	const auto metric = metricOf(p.metric), icMetric = metricOf(p.IC_metric);
	const double chi2 = p.IC_chi2_thres, ml = p.IC_ml_threshold;
	return [=](const std::vector<Eigen::Vector2d>& obs,
	           const std::vector<estimator::TAssocTarget>& pred)
	{
		std::vector<int> out(obs.size(), -1);
		if (obs.empty() || pred.empty()) return out;
		const size_t n = pred.size();
		mrpt::math::CMatrixDouble Z(obs.size(), 2), Y(n, 2), S(2 * n, 2 * n);
		S.setZero();
		for (size_t i = 0; i < obs.size(); ++i)
			for (int c = 0; c < 2; ++c) Z(i, c) = obs[i][c];
		for (size_t j = 0; j < n; ++j)
		{
			for (int c = 0; c < 2; ++c) Y(j, c) = pred[j].pred.p[c];
			S.asEigen().block<2, 2>(2 * j, 2 * j) = pred[j].pred.C;
		}
		mrpt::slam::TDataAssociationResults res;
		mrpt::slam::data_association_full_covariance(Z, Y, S, res, method, metric, chi2,
		                                             /*kd-tree*/ false, {}, icMetric, ml);
		for (const auto& [o, j] : res.associations) out.at(o) = int(j);
		return out;
	};
}
}  // namespace dynslam
