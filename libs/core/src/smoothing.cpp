#include <dynslam/core/models/se2.h>
#include <dynslam/core/models/smoothing.h>

#include <stdexcept>

namespace dynslam::models
{
Eigen::VectorXd smoothingResidual(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                  const Eigen::VectorXd& c, Eigen::MatrixXd* J_s_a,
                                  Eigen::MatrixXd* J_s_b, Eigen::MatrixXd* J_s_c)
{
	const Eigen::Index d = a.size();
	if ((d != 2 && d != 3) || b.size() != d || c.size() != d)
		throw std::invalid_argument("smoothingResidual: poses must all be 2- or 3-dimensional");
	Eigen::VectorXd s = (c - b) - (b - a);
	if (d == 3) s[2] = wrapToPi(wrapToPi(c[2] - b[2]) - wrapToPi(b[2] - a[2]));
	const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d, d);
	if (J_s_a) *J_s_a = I;
	if (J_s_b) *J_s_b = -2 * I;
	if (J_s_c) *J_s_c = I;
	return s;
}
}  // namespace dynslam::models
