#include <dynslam/core/models/gauge.h>
#include <dynslam/core/models/se2.h>

#include <stdexcept>

namespace dynslam::models
{
namespace
{
void checkSize(GaugeKind kind, const Eigen::VectorXd& v)
{
	const Eigen::Index want =
	    kind == GaugeKind::EgoPose || kind == GaugeKind::RelPose || kind == GaugeKind::Velocity3
	        ? 3
	        : 2;
	if (kind != GaugeKind::Invariant && v.size() != want)
		throw std::invalid_argument("gauge: block of " + std::to_string(v.size()) +
		                            " entries, expected " + std::to_string(want));
}
}  // namespace

Eigen::VectorXd gaugeTransform(GaugeKind kind, const Eigen::VectorXd& value,
                               const Eigen::Vector3d& delta, const Eigen::Vector2d& p0)
{
	checkSize(kind, value);
	const Eigen::Matrix2d R = rot2(delta[2]);
	Eigen::VectorXd out = value;
	switch (kind)
	{
		case GaugeKind::EgoPose:
			out.head<2>() = R * (value.head<2>() - p0) + p0 + delta.head<2>();
			out[2] = wrapToPi(value[2] + delta[2]);
			break;
		case GaugeKind::Point:
			out = R * (value.head<2>() - p0) + p0 + delta.head<2>();
			break;
		case GaugeKind::Vector:
		case GaugeKind::RelPose:
		case GaugeKind::Velocity3:
			out.head<2>() = R * value.head<2>();
			break;
		case GaugeKind::Invariant:
			break;
	}
	return out;
}

Eigen::MatrixXd J_block_delta(GaugeKind kind, const Eigen::VectorXd& value,
                              const Eigen::Vector2d& p0)
{
	checkSize(kind, value);
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(value.size(), 3);
	// d(R(a) w)/da at a = 0 is (-w_y, w_x).
	auto rotColumn = [&J](const Eigen::Vector2d& w)
	{
		J(0, 2) = -w.y();
		J(1, 2) = w.x();
	};
	switch (kind)
	{
		case GaugeKind::EgoPose:
			J.topLeftCorner<2, 2>().setIdentity();
			rotColumn(value.head<2>() - p0);
			J(2, 2) = 1;
			break;
		case GaugeKind::Point:
			J.topLeftCorner<2, 2>().setIdentity();
			rotColumn(value.head<2>() - p0);
			break;
		case GaugeKind::Vector:
		case GaugeKind::RelPose:
		case GaugeKind::Velocity3:
			rotColumn(value.head<2>());
			break;
		case GaugeKind::Invariant:
			break;
	}
	return J;
}

Eigen::MatrixXd addGaugeTerm(const Eigen::MatrixXd& P, const Eigen::MatrixXd& N,
                             const Eigen::Matrix3d& Sigma_0)
{
	if (N.rows() != P.rows() || N.cols() != 3 || P.rows() != P.cols())
		throw std::invalid_argument("addGaugeTerm: N must be P.rows() x 3, P square");
	return P + N * Sigma_0 * N.transpose();
}
}  // namespace dynslam::models
