/** The EKF step of object-centric motion models (issue 13): prediction of a subset. */
#include <dynslam/core/ekf_steps.h>

#include <Eigen/Cholesky>
#include <stdexcept>

namespace dynslam::ekf
{
void predictSubset(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                   const std::vector<int>& idx, const Eigen::VectorXd& x_new,
                   const Eigen::MatrixXd& F, const Eigen::MatrixXd& Q)
{
	const Eigen::Index m = Eigen::Index(idx.size());
	if (x_new.size() != m || F.rows() != m || F.cols() != m || Q.rows() != m || Q.cols() != m)
		throw std::invalid_argument("predictSubset: inconsistent sizes");
	if (P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("predictSubset: P does not match x");
	for (const int i : idx)
		if (i < 0 || i >= x.size()) throw std::out_of_range("predictSubset: state index");
	x(idx) = x_new;
	const Eigen::MatrixXd rows = F * P(idx, Eigen::all);  // m x n: rows of T P
	P(idx, Eigen::all) = rows;
	P(Eigen::all, idx) = rows.transpose();  // columns of T P T^T outside idx (P symmetric)
	Eigen::MatrixXd block = rows(Eigen::all, idx) * F.transpose() + Q;
	P(idx, idx) = 0.5 * (block + block.transpose());
}

}  // namespace dynslam::ekf
