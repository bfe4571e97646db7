#include <dynslam/apps/CDeadReckoningBackend.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/common/step_input.h>
#include <dynslam/core/models/se2.h>
#include <mrpt/math/CMatrixFixed.h>

#include <ostream>

namespace dynslam::apps
{
CDeadReckoningBackend::CDeadReckoningBackend() { reset(); }

void CDeadReckoningBackend::loadOptions(const mrpt::config::CConfigFileBase& ini)
{
	m_hasModel = config::has(ini, "DynamicKFSLAM", "measurement_model");
	m_model = TModelOptions();
	if (m_hasModel) m_model.loadFromConfigFile(ini, "DynamicKFSLAM");
	reset();
}

void CDeadReckoningBackend::dumpOptions(std::ostream& out) const
{
	out << "# " << name() << ": dead reckoning, "
	    << (m_hasModel ? "start, motion noise and parser of [DynamicKFSLAM]"
	                   : "no [DynamicKFSLAM]: x_0 = 0, P_0 = 0, the action's covariance")
	    << "\n";
	if (!m_hasModel) return;
	out << "initial_pose = " << config::formatMatrix(m_model.initial_pose.transpose()) << "\n";
	out << "Sigma_0      = " << config::formatMatrix(m_model.Sigma_0) << "\n";
	out << "motion_noise = " << (m_model.motion_noise_from_action ? "action" : "config") << "\n";
	if (!m_model.motion_noise_from_action)
		out << "Sigma_w      = " << config::formatMatrix(m_model.Sigma_w) << "\n";
}

void CDeadReckoningBackend::reset()
{
	m_x = m_hasModel ? m_model.initial_pose : Eigen::Vector3d::Zero();
	m_P = m_hasModel ? m_model.Sigma_0 : Eigen::Matrix3d::Zero();
	m_report = TStepReport();
}

void CDeadReckoningBackend::processActionObservation(
    const mrpt::obs::CActionCollection::Ptr& action, const mrpt::obs::CSensoryFrame::Ptr& SF)
{
	const TParseOptions opts = m_hasModel ? m_model.parseOptions() : TParseOptions();
	const estimator::TStepInput in = parseStepInput(action, SF, opts, name());
	const Eigen::Matrix3d& U =
	    m_hasModel && !m_model.motion_noise_from_action ? m_model.Sigma_w : in.U;
	Eigen::Matrix3d J_out_x, J_out_u;
	m_x = models::composePose(m_x, in.u, &J_out_x, &J_out_u);
	m_P = J_out_x * m_P * J_out_x.transpose() + J_out_u * U * J_out_u.transpose();
	m_P = (0.5 * (m_P + m_P.transpose())).eval();
	const int step = m_report.step + 1;
	m_report = TStepReport();
	m_report.step = step;
	onStep(in);
}

mrpt::poses::CPosePDFGaussian CDeadReckoningBackend::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	p.mean = mrpt::poses::CPose2D(m_x.x(), m_x.y(), m_x.z());
	p.cov = mrpt::math::CMatrixDouble33(m_P);
	return p;
}
}  // namespace dynslam::apps
