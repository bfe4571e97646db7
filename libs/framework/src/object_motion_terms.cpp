#include <dynslam/core/models/object_motion.h>
#include <dynslam/framework/object_motion_terms.h>

#include <stdexcept>

namespace dynslam::framework
{
CObjectMotionTerm::CObjectMotionTerm(std::shared_ptr<const estimator::IObjectMotionModel> model,
                                     const TVarKey& xiPrev, const TVarKey& vPrev, const TVarKey& xi,
                                     const TVarKey& v)
    : CTerm({xiPrev, vPrev, xi, v}), m_model(std::move(model))
{
	if (!m_model) throw std::invalid_argument("CObjectMotionTerm: null model");
}

TLinearization CObjectMotionTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	const Eigen::Index d = x[0].size(), dv = x[1].size();
	if (x[2].size() != d || x[3].size() != dv)
		throw std::invalid_argument("CObjectMotionTerm: block sizes differ between steps");
	Eigen::VectorXd s(d + dv);
	s << x[0], x[1];
	Eigen::MatrixXd F, Q;
	const Eigen::VectorXd f = m_model->predict(s, &F, &Q);
	TLinearization L;
	L.r.resize(d + dv);
	L.r << blockMinus(VarKind::ObjectPose, x[2], f.head(d)), x[3] - f.tail(dv);
	L.W = spdInverse(Q, "CObjectMotionTerm: the process noise of '" + m_model->name() +
	                        "' (every cv_accel_psd entry must be > 0 in the framework)");
	const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d + dv, d + dv);
	L.J = {-F.leftCols(d), -F.rightCols(dv), I.leftCols(d), I.rightCols(dv)};
	return L;
}

CObjectMixtureMotionTerm::CObjectMixtureMotionTerm(const TVarKey& xiPrev, const TVarKey& vPrev,
                                                   const TVarKey& xi, const TVarKey& v,
                                                   const Eigen::VectorXd& s_lin,
                                                   const models::TModeMixture& mix)
    : CTerm({xiPrev, vPrev, xi, v}),
      m_sLin(s_lin),
      m_mix(mix),
      m_info(spdInverse(mix.Q_eff, "CObjectMixtureMotionTerm: the mixture's process noise"))
{
	if (mix.s.size() != s_lin.size() || mix.F.rows() != s_lin.size() ||
	    mix.F.cols() != s_lin.size())
		throw std::invalid_argument("CObjectMixtureMotionTerm: sizes do not match");
}

TLinearization CObjectMixtureMotionTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	const Eigen::Index d = x[0].size(), dv = x[1].size();
	if (x[2].size() != d || x[3].size() != dv || d + dv != m_sLin.size())
		throw std::invalid_argument("CObjectMixtureMotionTerm: block sizes do not match");
	Eigen::VectorXd ds(d + dv);
	ds << blockMinus(VarKind::ObjectPose, x[0], m_sLin.head(d)), x[1] - m_sLin.tail(dv);
	const Eigen::VectorXd f = m_mix.s + m_mix.F * ds;
	TLinearization L;
	L.r.resize(d + dv);
	L.r << blockMinus(VarKind::ObjectPose, x[2], f.head(d)), x[3] - f.tail(dv);
	L.W = m_info;
	const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d + dv, d + dv);
	L.J = {-m_mix.F.leftCols(d), -m_mix.F.rightCols(dv), I.leftCols(d), I.rightCols(dv)};
	return L;
}

CObjectSightingTerm::CObjectSightingTerm(int t, const TVarKey& xi, const std::vector<TVarKey>& f0,
                                         int k, const Eigen::Vector2d& z,
                                         models::MeasurementModel model,
                                         const Eigen::Matrix2d& Sigma_v,
                                         const Eigen::Vector3d& sensor)
    : CTerm({TVarKey::ego(t), xi}),
      m_k(k),
      m_z(z),
      m_sensor(sensor),
      m_model(model),
      m_info(spdInverse(Sigma_v, "CObjectSightingTerm: Sigma_v"))
{
	if (k < 0 || size_t(k) >= f0.size())
		throw std::invalid_argument("CObjectSightingTerm: feature index out of range");
	m_keys.insert(m_keys.end(), f0.begin(), f0.end());
}

TLinearization CObjectSightingTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	const Eigen::Index n = Eigen::Index(x.size()) - 2;
	Eigen::Matrix2Xd f0(2, n);
	for (Eigen::Index j = 0; j < n; ++j) f0.col(j) = x[size_t(2 + j)];
	models::Matrix23d Hx;
	Eigen::MatrixXd H_xi, H_f0;
	const Eigen::Vector2d zhat = models::observeObjectFeatureFromSensor(
	    m_model, x[0], m_sensor, x[1], f0, m_k, &Hx, &H_xi, &H_f0);
	TLinearization L;
	L.r = models::innovation(m_model, m_z, zhat);
	L.W = m_info;
	L.J = {-Eigen::MatrixXd(Hx), -H_xi};
	for (Eigen::Index j = 0; j < n; ++j) L.J.push_back(-H_f0.middleCols(2 * j, 2));
	return L;
}

CObjectVelocityInitTerm::CObjectVelocityInitTerm(
    std::shared_ptr<const estimator::IObjectMotionModel> model, const TVarKey& xi, const TVarKey& v,
    int steps, int poseDim)
    : CTerm({xi, v}), m_model(std::move(model)), m_steps(steps)
{
	if (!m_model) throw std::invalid_argument("CObjectVelocityInitTerm: null model");
	Eigen::MatrixXd J, Sigma;
	m_model->initialVelocity(Eigen::VectorXd::Zero(poseDim), steps, &J, &Sigma);
	m_info = spdInverse(Sigma, "CObjectVelocityInitTerm: the velocity prior");
}

TLinearization CObjectVelocityInitTerm::linearize(const std::vector<Eigen::VectorXd>& x) const
{
	Eigen::MatrixXd J_v_xi;
	const Eigen::VectorXd v0 = m_model->initialVelocity(x[0], m_steps, &J_v_xi, nullptr);
	TLinearization L;
	L.r = x[1] - v0;
	L.W = m_info;
	L.J = {-J_v_xi, Eigen::MatrixXd::Identity(x[1].size(), x[1].size())};
	return L;
}
}  // namespace dynslam::framework
