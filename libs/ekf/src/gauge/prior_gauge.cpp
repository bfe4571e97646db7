/** The prior gauge (prior_gauge.h). */
#include "prior_gauge.h"

#include <dynslam/core/models/gauge.h>

#include <stdexcept>

namespace dynslam::ekf
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

Eigen::Matrix3d CPriorGauge::reset()
{
	m_origin = m_options.initial_pose.head<2>();
	return m_options.prior_gauge_anchor ? Eigen::Matrix3d::Zero().eval() : m_options.Sigma_0;
}

Eigen::MatrixXd CPriorGauge::term(const TBlock* block, const Eigen::VectorXd& mean) const
{
	const Eigen::Index n = mean.size();
	if (!m_options.prior_gauge_anchor) return Eigen::MatrixXd::Zero(n, n);
	const models::GaugeKind k = block ? gaugeKind(*block) : models::GaugeKind::EgoPose;
	const Eigen::MatrixXd J = models::J_block_delta(k, mean, m_origin);
	return J * m_options.Sigma_0 * J.transpose();
}

Eigen::MatrixXd CPriorGauge::jacobian(const estimator::CPaddedLayout& layout,
                                      const Eigen::VectorXd& x,
                                      const estimator::IObjectMotionModel& motion) const
{
	Eigen::MatrixXd N = Eigen::MatrixXd::Zero(x.size(), 3);
	N.topRows<3>() = models::J_block_delta(models::GaugeKind::EgoPose, x.head<3>(), m_origin);
	for (size_t b = 0; b < layout.size(); ++b)
	{
		const TBlock& t = layout[b];
		const std::vector<int> idx = layout.indices(b);
		// A velocity block beyond the velocity (ca: [v; a]) is made of parts of the velocity's
		// shape (pose dim d: velocityDim(d) entries), each a derivative that rotates like it.
		const int d = t.kind == BlockKind::ObjectVelocity && motion.velocityDim(3) == t.dim ? 3
		              : t.kind == BlockKind::ObjectVelocity && motion.velocityDim(2) == t.dim
		                  ? 2
		                  : t.dim;
		TBlock part = t;
		part.dim = d;
		for (int i = 0; i + d <= t.dim; i += d)
		{
			const std::vector<int> pi(idx.begin() + i, idx.begin() + i + d);
			N(pi, Eigen::all) = models::J_block_delta(gaugeKind(part), x(pi).eval(), m_origin);
		}
	}
	return N;
}

Eigen::MatrixXd CPriorGauge::reported(Eigen::MatrixXd P, const estimator::CPaddedLayout& layout,
                                      const Eigen::VectorXd& x,
                                      const estimator::IObjectMotionModel& motion) const
{
	if (!m_options.prior_gauge_anchor) return P;
	return models::addGaugeTerm(P, jacobian(layout, x, motion), m_options.Sigma_0);
}
}  // namespace dynslam::ekf
