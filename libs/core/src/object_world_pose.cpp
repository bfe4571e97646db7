#include <dynslam/core/models/object_world_pose.h>

#include <stdexcept>

namespace dynslam::models
{
Eigen::VectorXd objectWorldPose(const Eigen::VectorXd& xi, const Eigen::Matrix2Xd& f0,
                                Eigen::MatrixXd* J_w_in)
{
	const Eigen::Index d = xi.size(), n = f0.cols();
	if ((d != 2 && d != 3) || n < 1)
		throw std::invalid_argument(
		    "objectWorldPose: the pose has 2 or 3 entries and the object at least one founder");
	const Eigen::Vector2d c0 = f0.rowwise().mean();
	Eigen::VectorXd w = xi;
	w.head<2>() += c0;
	if (J_w_in)
	{
		J_w_in->setZero(d, d + 2 * n);
		J_w_in->leftCols(d).setIdentity();
		for (Eigen::Index k = 0; k < n; ++k)
			J_w_in->block<2, 2>(0, d + 2 * k) = Eigen::Matrix2d::Identity() / double(n);
	}
	return w;
}
}  // namespace dynslam::models
