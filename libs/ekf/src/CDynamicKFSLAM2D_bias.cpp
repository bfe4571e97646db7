/** CDynamicKFSLAM2D: the odometry bias block (options.odometry_bias, issue 17; the model is
 * dynslam/core/models/odometry_bias.h, the prediction ekf::propagateWithBias). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <cmath>
#include <stdexcept>

namespace dynslam
{
void CDynamicKFSLAM2D::addOdometryBiasBlock()
{
	if (!m_layout.empty() || m_xkk.size() != 3)
		throw std::logic_error("CDynamicKFSLAM2D: the odometry bias is added to an empty map");
	estimator::TBlock b;
	b.kind = estimator::BlockKind::OdometryBias;
	b.step = 0;
	b.dim = options.odometry_bias.dim();
	m_layout.append(b);
	const size_t n = size_t(m_layout.storageDim());
	ekf::RowMatrixXd P = ekf::RowMatrixXd::Zero(Eigen::Index(n), Eigen::Index(n));
	P.topLeftCorner<3, 3>() = cov().topLeftCorner<3, 3>();
	const Eigen::MatrixXd B = options.odometry_bias.prior();
	P(3, 3) = B(0, 0);
	P(4, 4) = b.dim == 2 ? B(1, 1) : 1.0;  // s, or the pad (mean 0, variance 1)
	setCov(P);
	m_xkk.resize(n);
	m_xkk[3] = 0;
	m_xkk[4] = 0;
}

double CDynamicKFSLAM2D::odometryDt()
{
	const double t = m_in.stamp, last = m_lastStamp;
	m_lastStamp = t;
	// The first step has no step before it to take a duration from (the simulator's ACT_0 is
	// a zero increment): no bias correction, no random walk.
	if (m_step == 0) return 0;
	if (std::isfinite(t) && std::isfinite(last) && t > last) return t - last;
	return options.odometry_bias.odometry_dt;
}

bool CDynamicKFSLAM2D::mapEmpty() const
{
	return m_layout.size() == (options.odometry_bias.enabled() ? 1u : 0u);
}

std::optional<std::pair<Eigen::VectorXd, Eigen::MatrixXd>> CDynamicKFSLAM2D::getOdometryBias() const
{
	if (m_layout.empty() || m_layout[0].kind != estimator::BlockKind::OdometryBias)
		return std::nullopt;
	const std::vector<int> idx = m_layout.indices(0);
	return std::make_pair(Eigen::VectorXd(m_xkk.asEigen()(idx)), ekf::marginal(cov(), idx));
}
}  // namespace dynslam
