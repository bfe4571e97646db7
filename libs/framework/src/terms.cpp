#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/core/models/smoothing.h>
#include <dynslam/framework/terms.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <stdexcept>

namespace dynslam::framework
{
Eigen::MatrixXd spdInverse(const Eigen::MatrixXd& A, const std::string& what)
{
	if (A.rows() != A.cols() || !A.allFinite())
		throw std::invalid_argument(what + ": not a finite square matrix");
	const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (A + A.transpose()));
	if (llt.info() != Eigen::Success)
		throw std::invalid_argument(what + ": covariance not positive definite");
	Eigen::MatrixXd inv = llt.solve(Eigen::MatrixXd::Identity(A.rows(), A.cols()));
	return 0.5 * (inv + inv.transpose());
}

bool CTerm::touches(const TVarKey& k) const
{
	return std::find(m_keys.begin(), m_keys.end(), k) != m_keys.end();
}

// ---------------------------------------------------------------------------------------
CPriorTerm::CPriorTerm(std::vector<TVarKey> keys, std::vector<int> dims, Eigen::VectorXd mean,
                       Eigen::MatrixXd information)
    : CTerm(std::move(keys)),
      m_dims(std::move(dims)),
      m_mean(std::move(mean)),
      m_info(std::move(information))
{
	int n = 0;
	for (int d : m_dims) n += d;
	if (m_dims.size() != m_keys.size() || m_mean.size() != n || m_info.rows() != n ||
	    m_info.cols() != n)
		throw std::invalid_argument("CPriorTerm: inconsistent sizes");
	if (!m_mean.allFinite() || !m_info.allFinite())
		throw std::invalid_argument("CPriorTerm: mean or information not finite");
}

std::shared_ptr<CPriorTerm> CPriorTerm::fromCovariance(std::vector<TVarKey> keys,
                                                       std::vector<int> dims, Eigen::VectorXd mean,
                                                       const Eigen::MatrixXd& covariance)
{
	return std::make_shared<CPriorTerm>(std::move(keys), std::move(dims), std::move(mean),
	                                    spdInverse(covariance, "CPriorTerm::fromCovariance"));
}

TLinearization CPriorTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	TLinearization L;
	const Eigen::Index n = m_mean.size();
	L.r.resize(n);
	L.W = m_info;
	L.J.resize(m_keys.size());
	int off = 0;
	for (size_t i = 0; i < m_keys.size(); ++i)
	{
		const int d = m_dims[i];
		L.r.segment(off, d) = blockMinus(m_keys[i].kind, x[i], m_mean.segment(off, d));
		L.J[i] = Eigen::MatrixXd::Zero(n, d);
		L.J[i].block(off, 0, d, d).setIdentity();
		off += d;
	}
	return L;
}

// ---------------------------------------------------------------------------------------
COdometryTerm::COdometryTerm(int t_from, int t_to, const Eigen::Vector3d& u,
                             const Eigen::Matrix3d& Sigma_u)
    : CTerm({TVarKey::ego(t_from), TVarKey::ego(t_to)}), m_u(u), m_Sigma_u(Sigma_u)
{
	spdInverse(Sigma_u, "COdometryTerm: Sigma_u");
}

TLinearization COdometryTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	Eigen::Matrix3d F, G;
	const Eigen::Vector3d pred = models::composePose(x[0], m_u, &F, &G);
	TLinearization L;
	L.r = blockMinus(VarKind::EgoPose, x[1], pred);
	L.J = {-Eigen::MatrixXd(F), Eigen::MatrixXd::Identity(3, 3)};
	L.W = spdInverse(G * m_Sigma_u * G.transpose(), "COdometryTerm: G Sigma_u G^T");
	return L;
}

// ---------------------------------------------------------------------------------------
CMeasurementTerm::CMeasurementTerm(int t, const TVarKey& feature, const Eigen::Vector2d& z,
                                   models::MeasurementModel model, const Eigen::Matrix2d& Sigma_v,
                                   const Eigen::Vector3d& sensor)
    : CTerm({TVarKey::ego(t), feature}),
      m_z(z),
      m_sensor(sensor),
      m_model(model),
      m_info(spdInverse(Sigma_v, "CMeasurementTerm: Sigma_v"))
{
}

TLinearization CMeasurementTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	models::Matrix23d Hx;
	Eigen::Matrix2d Hf;
	const Eigen::Vector2d zhat = models::observeFromSensor(m_model, x[0], m_sensor, x[1], &Hx, &Hf);
	TLinearization L;
	L.r = models::innovation(m_model, m_z, zhat);
	L.J = {-Eigen::MatrixXd(Hx), -Eigen::MatrixXd(Hf)};
	L.W = m_info;
	return L;
}

// ---------------------------------------------------------------------------------------
namespace
{
std::vector<TVarKey> poseKeys(const TObjectPoseKeys& k)
{
	if (k.f0.empty() || k.ft.empty() || k.ft.size() != k.seen.size())
		throw std::invalid_argument("object pose term: need f0, ft and seen of equal size");
	for (int s : k.seen)
		if (s < 0 || size_t(s) >= k.f0.size())
			throw std::invalid_argument("object pose term: seen index out of range");
	std::vector<TVarKey> keys{k.pose};
	keys.insert(keys.end(), k.f0.begin(), k.f0.end());
	keys.insert(keys.end(), k.ft.begin(), k.ft.end());
	return keys;
}
}  // namespace

CObjectPoseFeatureTerm::CObjectPoseFeatureTerm(const TObjectPoseKeys& k,
                                               const Eigen::Matrix2d& Sigma_xi)
    : CTerm(poseKeys(k)),
      m_n(k.f0.size()),
      m_m(k.ft.size()),
      m_seen(k.seen),
      m_info(spdInverse(Sigma_xi, "CObjectPoseFeatureTerm: Sigma_xi"))
{
}

TLinearization CObjectPoseFeatureTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	const Eigen::Index d = x[0].size();
	Eigen::Matrix2Xd f0(2, m_n);
	for (size_t k = 0; k < m_n; ++k) f0.col(k) = x[1 + k];
	Eigen::Matrix2Xd pred;
	Eigen::MatrixXd J_xi, J_f0;
	if (d == 2)
	{
		if (m_n != 1) throw std::invalid_argument("translation-only pose needs one feature");
		pred = f0.colwise() + Eigen::Vector2d(x[0]);
		J_xi = Eigen::MatrixXd::Identity(2, 2);
		J_f0 = Eigen::MatrixXd::Identity(2, 2);
	}
	else
		pred = models::objectPoseMap(Eigen::Vector3d(x[0]), f0, &J_xi, &J_f0);

	TLinearization L;
	L.r.resize(2 * m_m);
	L.W = Eigen::MatrixXd::Zero(2 * m_m, 2 * m_m);
	L.J.assign(1 + m_n + m_m, Eigen::MatrixXd());
	L.J[0] = Eigen::MatrixXd::Zero(2 * m_m, d);
	for (size_t k = 0; k < m_n; ++k) L.J[1 + k] = Eigen::MatrixXd::Zero(2 * m_m, 2);
	for (size_t i = 0; i < m_m; ++i)
	{
		const int s = m_seen[i];
		L.r.segment<2>(2 * i) = x[1 + m_n + i] - pred.col(s);
		L.W.block<2, 2>(2 * i, 2 * i) = m_info;
		L.J[0].middleRows(2 * i, 2) = -J_xi.middleRows(2 * s, 2);
		for (size_t k = 0; k < m_n; ++k)
			L.J[1 + k].middleRows(2 * i, 2) = -J_f0.block(2 * s, 2 * k, 2, 2);
		L.J[1 + m_n + i] = Eigen::MatrixXd::Zero(2 * m_m, 2);
		L.J[1 + m_n + i].middleRows(2 * i, 2).setIdentity();
	}
	return L;
}

// ---------------------------------------------------------------------------------------
CObjectPosePoseTerm::CObjectPosePoseTerm(const TObjectPoseKeys& k, const Eigen::Matrix2d& Sigma_xi)
    : CTerm(poseKeys(k)), m_n(k.f0.size()), m_m(k.ft.size()), m_seen(k.seen), m_Sigma_xi(Sigma_xi)
{
	spdInverse(Sigma_xi, "CObjectPosePoseTerm: Sigma_xi");
}

TLinearization CObjectPosePoseTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	const Eigen::Index d = x[0].size();
	Eigen::Matrix2Xd f0(2, m_n), ft(2, m_m);
	for (size_t k = 0; k < m_n; ++k) f0.col(k) = x[1 + k];
	for (size_t i = 0; i < m_m; ++i) ft.col(i) = x[1 + m_n + i];
	Eigen::VectorXd xi;
	Eigen::MatrixXd G1, G2;
	if (d == 2)
	{
		if (m_n != 1 || m_m != 1)
			throw std::invalid_argument("translation-only pose needs one feature");
		Eigen::Matrix2d g1, g2;
		xi = models::objectTranslationInverse(f0.col(0), ft.col(0), &g1, &g2);
		G1 = g1;
		G2 = g2;
	}
	else
		xi = models::objectPoseInverse(f0, ft, m_seen, &G1, &G2);

	TLinearization L;
	L.r = blockMinus(VarKind::ObjectPose, x[0], xi);
	L.J.assign(1 + m_n + m_m, Eigen::MatrixXd());
	L.J[0] = Eigen::MatrixXd::Identity(d, d);
	for (size_t k = 0; k < m_n; ++k) L.J[1 + k] = -G1.middleCols(2 * k, 2);
	for (size_t i = 0; i < m_m; ++i) L.J[1 + m_n + i] = -G2.middleCols(2 * i, 2);
	Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(d, d);
	for (size_t i = 0; i < m_m; ++i)
		Q += G2.middleCols(2 * i, 2) * m_Sigma_xi * G2.middleCols(2 * i, 2).transpose();
	L.W = spdInverse(Q, "CObjectPosePoseTerm: Gamma2 diag(Sigma_xi) Gamma2^T");
	return L;
}

// ---------------------------------------------------------------------------------------
CSmoothingTerm::CSmoothingTerm(const TVarKey& a, const TVarKey& b, const TVarKey& c,
                               const Eigen::MatrixXd& Sigma_s)
    : CTerm({a, b, c}), m_info(spdInverse(Sigma_s, "CSmoothingTerm: Sigma_s"))
{
}

TLinearization CSmoothingTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	if (x[0].size() != m_info.rows())
		throw std::invalid_argument("CSmoothingTerm: pose size differs from Sigma_s");
	TLinearization L;
	L.J.resize(3);
	L.r = models::smoothingResidual(x[0], x[1], x[2], &L.J[0], &L.J[1], &L.J[2]);
	L.W = m_info;
	return L;
}

// ---------------------------------------------------------------------------------------
namespace
{
std::vector<TVarKey> poseKeys(const estimator::TPseudoMeasurement& m)
{
	std::vector<TVarKey> keys;
	for (const int t : m.steps) keys.push_back(TVarKey::objectPose(m.object, t));
	return keys;
}
}  // namespace

CMotionModelTerm::CMotionModelTerm(std::shared_ptr<const estimator::IObjectMotionModel> model,
                                   const estimator::TPseudoMeasurement& m)
    : CTerm(poseKeys(m)),
      m_model(std::move(model)),
      m_meas(m),
      m_info(spdInverse(m.R, "CMotionModelTerm: R"))
{
	if (!m_model) throw std::invalid_argument("CMotionModelTerm: null model");
}

TLinearization CMotionModelTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	for (const auto& v : x)
		if (v.size() != m_meas.dim)
			throw std::invalid_argument("CMotionModelTerm: pose size differs from the model's");
	TLinearization L;
	L.r = m_model->residual(m_meas, x, &L.J);
	L.W = m_info;
	return L;
}

// ---------------------------------------------------------------------------------------
CBodyPoseMeasurementTerm::CBodyPoseMeasurementTerm(int t, const TVarKey& body,
                                                   const Eigen::VectorXd& T,
                                                   const Eigen::MatrixXd& Sigma_T)
    : CTerm({TVarKey::ego(t), body}),
      m_T(T),
      m_info(spdInverse(Sigma_T, "CBodyPoseMeasurementTerm: Sigma_T"))
{
	if (T.size() != 2 && T.size() != 3)
		throw std::invalid_argument("CBodyPoseMeasurementTerm: T must have 2 or 3 entries");
	if (Sigma_T.rows() != T.size())
		throw std::invalid_argument("CBodyPoseMeasurementTerm: Sigma_T size differs from T");
}

TLinearization CBodyPoseMeasurementTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	const Eigen::Index d = m_T.size();
	if (x[1].size() != d) throw std::invalid_argument("CBodyPoseMeasurementTerm: body pose size");
	models::Matrix23d Jx;
	Eigen::Matrix2d Jp;
	const Eigen::Vector2d p = models::cartesianObserve(x[0], x[1].head<2>(), &Jx, &Jp);
	TLinearization L;
	L.r.resize(d);
	L.r.head<2>() = m_T.head<2>() - p;
	Eigen::MatrixXd J_x = Eigen::MatrixXd::Zero(d, 3), J_o = Eigen::MatrixXd::Zero(d, d);
	J_x.topRows<2>() = -Jx;
	J_o.topLeftCorner<2, 2>() = -Jp;
	if (d == 3)
	{
		L.r[2] = models::wrapToPi(m_T[2] - (x[1][2] - x[0][2]));
		J_x(2, 2) = 1;
		J_o(2, 2) = -1;
	}
	L.J = {J_x, J_o};
	L.W = m_info;
	return L;
}
}  // namespace dynslam::framework
