/** The odometry-bias module (odometry_bias.h). */
#include "odometry_bias.h"

#include <dynslam/core/ekf_odometry_bias.h>

#include <cmath>
#include <stdexcept>

namespace dynslam::ekf
{
std::unique_ptr<COdometryBiasModule> makeOdometryBiasModule(TFilterAccess& a)
{
	if (!a.options().odometry_bias.enabled()) return nullptr;
	return std::make_unique<COdometryBiasModule>(a.options().odometry_bias);
}

void COdometryBiasModule::addBlock(TFilterAccess& a) const
{
	if (!a.layout().empty() || a.mean().size() != 3)
		throw std::logic_error("CDynamicKFSLAM2D: the odometry bias is added to an empty map");
	estimator::TBlock b;
	b.kind = estimator::BlockKind::OdometryBias;
	b.step = 0;
	b.dim = m_options.dim();
	// The mean 0, the diagonal prior, no correlation with the ego (and a pad for rate).
	a.augment(b, Eigen::VectorXd::Zero(b.dim), {}, Eigen::MatrixXd(b.dim, 0), m_options.prior());
}

double COdometryBiasModule::stepDuration(double stamp, int step)
{
	const double last = m_lastStamp;
	m_lastStamp = stamp;
	// The first step has no step before it to take a duration from (the simulator's ACT_0 is
	// a zero increment): no bias correction, no random walk.
	if (step == 0) return 0;
	if (std::isfinite(stamp) && std::isfinite(last) && stamp > last) return stamp - last;
	return m_options.odometry_dt;
}

void COdometryBiasModule::propagate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                                    const Eigen::Vector3d& u, const Eigen::Matrix3d& S, int index,
                                    double dt, const Eigen::Vector3d* fejPrev,
                                    Eigen::Matrix3d& F) const
{
	ekf::propagateWithBias(x, P, u, S, m_options.block(index), dt, fejPrev, &F);
}

std::optional<std::pair<Eigen::VectorXd, Eigen::MatrixXd>> COdometryBiasModule::estimate(
    const TFilterView::TStateRef& s)
{
	if (s.layout.empty() || s.layout[0].kind != estimator::BlockKind::OdometryBias)
		return std::nullopt;
	const std::vector<int> idx = s.layout.indices(0);
	return std::make_pair(Eigen::VectorXd(s.x(idx)), ekf::marginal(s.P, idx));
}
}  // namespace dynslam::ekf
