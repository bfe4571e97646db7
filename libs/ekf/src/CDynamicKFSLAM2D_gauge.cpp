/** CDynamicKFSLAM2D: the prior gauge (prior_gauge = anchor, doc/state-layout.md "The prior
 * gauge"): the output term N Sigma_0 N^T of the reported covariances. */
#include <dynslam/core/models/gauge.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <stdexcept>

namespace dynslam
{
using estimator::BlockKind;
using estimator::TBlock;

namespace
{
/** How a block transforms under the global rigid transform (models/gauge.h). */
models::GaugeKind gaugeKind(const TBlock& t)
{
	switch (t.kind)
	{
		case BlockKind::StaticLandmark:
		case BlockKind::ObjectFeature0:
		case BlockKind::ObjectFeatureT:
			return models::GaugeKind::Point;
		case BlockKind::ObjectPose:
			return t.dim == 3 ? models::GaugeKind::RelPose : models::GaugeKind::Vector;
		case BlockKind::ObjectVelocity:
			return t.dim == 3 ? models::GaugeKind::Velocity3 : models::GaugeKind::Vector;
		case BlockKind::OdometryBias:
			return models::GaugeKind::Invariant;
		case BlockKind::Compressed:
			break;
	}
	throw std::logic_error("gauge: a compressed block has no transform (expand the state first)");
}
}  // namespace

Eigen::MatrixXd CDynamicKFSLAM2D::gaugeTerm(const TBlock* block, const Eigen::VectorXd& mean) const
{
	const Eigen::Index n = mean.size();
	if (!options.prior_gauge_anchor) return Eigen::MatrixXd::Zero(n, n);
	const models::GaugeKind k = block ? gaugeKind(*block) : models::GaugeKind::EgoPose;
	const Eigen::MatrixXd J = models::J_block_delta(k, mean, m_gaugeOrigin);
	return J * options.Sigma_0 * J.transpose();
}

Eigen::MatrixXd CDynamicKFSLAM2D::gaugeJacobian() const
{
	const TStateRef s = wholeState();
	const Eigen::VectorXd x = s.x;
	Eigen::MatrixXd N = Eigen::MatrixXd::Zero(x.size(), 3);
	N.topRows<3>() = models::J_block_delta(models::GaugeKind::EgoPose, x.head<3>(), m_gaugeOrigin);
	for (size_t b = 0; b < s.layout.size(); ++b)
	{
		const TBlock& t = s.layout[b];
		const std::vector<int> idx = s.layout.indices(b);
		// A velocity block beyond the velocity (ca: [v; a]) is made of parts of the velocity's
		// shape (pose dim d: velocityDim(d) entries), each a derivative that rotates like it.
		const int d = t.kind == BlockKind::ObjectVelocity && m_motion->velocityDim(3) == t.dim ? 3
		              : t.kind == BlockKind::ObjectVelocity && m_motion->velocityDim(2) == t.dim
		                  ? 2
		                  : t.dim;
		TBlock part = t;
		part.dim = d;
		for (int i = 0; i + d <= t.dim; i += d)
		{
			const std::vector<int> pi(idx.begin() + i, idx.begin() + i + d);
			N(pi, Eigen::all) = models::J_block_delta(gaugeKind(part), x(pi).eval(), m_gaugeOrigin);
		}
	}
	return N;
}

Eigen::MatrixXd CDynamicKFSLAM2D::reportedCov() const
{
	const Eigen::MatrixXd P = fullCov().asEigen();
	if (!options.prior_gauge_anchor) return P;
	return models::addGaugeTerm(P, gaugeJacobian(), options.Sigma_0);
}
}  // namespace dynslam
