/** The EKF steps of object-centric motion models (issue 13): prediction of a subset and the
 * update that corrects only a subset (Schmidt, cv_ego_velocity_std). */
#include <dynslam/ekf_steps.h>

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

double schmidtUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                     const std::vector<int>& idx, const std::vector<int>& upd,
                     const Eigen::MatrixXd& H, const Eigen::VectorXd& nu, const Eigen::MatrixXd& R)
{
	const Eigen::Index m = H.rows();
	if (H.cols() != Eigen::Index(idx.size()) || nu.size() != m || R.rows() != m || R.cols() != m)
		throw std::invalid_argument("schmidtUpdate: inconsistent sizes");
	if (P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("schmidtUpdate: P does not match x");
	for (const auto* v : {&idx, &upd})
		for (const int i : *v)
			if (i < 0 || i >= x.size()) throw std::out_of_range("schmidtUpdate: state index");
	if (m == 0) return 0.0;
	const Eigen::MatrixXd A = H * P(idx, Eigen::all);  // m x n: H P[idx,:]
	Eigen::MatrixXd S = A(Eigen::all, idx) * H.transpose() + R;
	S = 0.5 * (S + S.transpose());
	const Eigen::LLT<Eigen::MatrixXd> llt(S);
	if (llt.info() != Eigen::Success)
		throw std::runtime_error("schmidtUpdate: innovation covariance not positive definite");
	const Eigen::MatrixXd K_u = llt.solve(A(Eigen::all, upd)).transpose();  // |upd| x m
	x(upd) += K_u * nu;
	const Eigen::MatrixXd rows = P(upd, Eigen::all) - K_u * A;  // |upd| x n
	P(upd, Eigen::all) = rows;
	P(Eigen::all, upd) = rows.transpose();
	const Eigen::MatrixXd block = rows(Eigen::all, upd);
	P(upd, upd) = 0.5 * (block + block.transpose());
	return nu.dot(llt.solve(nu));
}
}  // namespace dynslam::ekf
