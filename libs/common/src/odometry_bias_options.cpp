/** TOdometryBiasOptions: odometry_bias ([DynamicKFSLAM]) and the keys of [OdometryBias]. */
#include <dynslam/common/config_utils.h>
#include <dynslam/common/model_keys.h>
#include <dynslam/common/odometry_bias_options.h>

#include <ostream>

namespace dynslam
{
void TOdometryBiasOptions::load(const mrpt::config::CConfigFileBase& c, const std::string& core)
{
	using namespace dynslam::config;
	const std::vector<std::string> modes{"none", "rate", "rate_scale"};
	mode = modes[size_t(readChoice(c, core, "odometry_bias", modes, 0))];
	*this = TOdometryBiasOptions{mode};
	if (!enabled()) return;
	const std::string s = kOdometryBiasSection;
	odometry_dt = readPositive(c, s, "odometry_dt", 0, true);
	rate_std0 = readPositive(c, s, "bias_rate_std0", 0, true);
	rate_rw = readNonNegative(c, s, "bias_rate_rw", 0, true);
	if (dim() == 2)
	{
		scale_std0 = readPositive(c, s, "bias_scale_std0", 0, true);
		scale_rw = readNonNegative(c, s, "bias_scale_rw", 0, true);
	}
}

ekf::TOdometryBiasBlock TOdometryBiasOptions::block(int index) const
{
	ekf::TOdometryBiasBlock b;
	b.index = index;
	b.dim = dim();
	b.q = Eigen::Vector2d(rate_rw * rate_rw, scale_rw * scale_rw);
	return b;
}

Eigen::MatrixXd TOdometryBiasOptions::prior() const
{
	const Eigen::Vector2d v(rate_std0 * rate_std0, scale_std0 * scale_std0);
	return Eigen::MatrixXd(v.head(dim()).asDiagonal());
}

void TOdometryBiasOptions::dump(std::ostream& out) const
{
	if (!enabled()) return;
	out << "\n[" << kOdometryBiasSection << "]\n";
	out << "odometry_dt                    = " << odometry_dt << "\n";
	out << "bias_rate_std0                 = " << rate_std0 << "\n";
	out << "bias_rate_rw                   = " << rate_rw << "\n";
	if (dim() == 2)
	{
		out << "bias_scale_std0                = " << scale_std0 << "\n";
		out << "bias_scale_rw                  = " << scale_rw << "\n";
	}
}
}  // namespace dynslam
