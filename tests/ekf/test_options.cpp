/** TOptions: required keys, invalid values and the dump round trip. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <sstream>

using namespace dynslam;

namespace
{
const char* kGood = R"([DynamicKFSLAM]
measurement_model = cartesian
Sigma_v = [1e-5 1e-5]
motion_noise = action
Sigma_0 = [1e-6 1e-6 1e-8]
Sigma_xi = [0.1 0.1]
smoothing = false
keep_last_poses = 2
[DynamicKFSLAM_KalmanFilter]
method = kfEKFNaive
)";

std::string loadError(const std::string& ini)
{
	mrpt::config::CConfigFileMemory c(ini);
	CDynamicKFSLAM2D f;
	try
	{
		f.loadOptions(c);
	}
	catch (const std::exception& e)
	{
		return e.what();
	}
	return "";
}
std::string replaced(const std::string& key, const std::string& line)
{
	std::string s = kGood;
	const auto p = s.find(key + " =");
	if (p == std::string::npos) return s + "\n";
	const auto e = s.find('\n', p);
	return s.substr(0, p) + line + s.substr(e);
}
}  // namespace

TEST(DynamicOptions, GoodFileLoads)
{
	mrpt::config::CConfigFileMemory c(kGood);
	CDynamicKFSLAM2D f;
	f.loadOptions(c);
	EXPECT_EQ(f.options.measurement_model, models::MeasurementModel::Cartesian);
	EXPECT_EQ(f.options.Sigma_v(1, 1), 1e-5);
	EXPECT_EQ(f.options.keep_last_poses, 2);
	EXPECT_EQ(f.fullCov()(2, 2), 1e-8);  // reset() applied Sigma_0
}

TEST(DynamicOptions, RequiredKeysThrowNamingThem)
{
	EXPECT_NE(loadError(replaced("measurement_model", "")).find("measurement_model: required"),
	          std::string::npos);
	EXPECT_NE(loadError(replaced("Sigma_v", "")).find("Sigma_v: required"), std::string::npos);
	// motion_noise = config makes Sigma_w required
	EXPECT_NE(
	    loadError(replaced("motion_noise", "motion_noise = config")).find("Sigma_w: required"),
	    std::string::npos);
}

TEST(DynamicOptions, InvalidValuesNameSectionKeyAndValue)
{
	const auto e1 = loadError(replaced("Sigma_v", "Sigma_v = [1e-5 -1e-5]"));
	EXPECT_NE(e1.find("[DynamicKFSLAM] Sigma_v = '[1e-5 -1e-5]'"), std::string::npos) << e1;
	EXPECT_NE(e1.find("positive definite"), std::string::npos) << e1;
	const auto e2 = loadError(replaced("measurement_model", "measurement_model = polar"));
	EXPECT_NE(e2.find("measurement_model = 'polar'"), std::string::npos) << e2;
	const auto e3 = loadError(replaced("keep_last_poses", "keep_last_poses = 0"));
	EXPECT_NE(e3.find("keep_last_poses"), std::string::npos) << e3;
	const auto e4 = loadError(replaced("smoothing", "smoothing = true\nSigma_s = [1 1 1]"));
	EXPECT_NE(e4.find("keep_last_poses >= 3"), std::string::npos) << e4;
	const auto e5 = loadError(replaced("Sigma_xi", "Sigma_xi = [0.1 0.2; 0.3 0.1]"));
	EXPECT_NE(e5.find("not symmetric"), std::string::npos) << e5;
	const auto e6 = loadError(replaced("Sigma_0", "Sigma_0 = [1e-6 abc 1e-8]"));
	EXPECT_NE(e6.find("'abc' is not a number"), std::string::npos) << e6;
	const auto e7 = loadError(replaced("Sigma_0", "Sigma_0 = [1e-6 1e-8]"));
	EXPECT_NE(e7.find("expected a 3x3 covariance"), std::string::npos) << e7;
	const auto e8 = loadError(std::string(kGood) + "[DynamicKFSLAM]\nsmoothin = true\n");
	EXPECT_NE(e8.find("unknown key"), std::string::npos) << e8;
	const auto e9 = loadError(replaced("method", "method = kfIKF"));
	EXPECT_NE(e9.find("only kfEKFNaive and kfEKFAlaDavison"), std::string::npos) << e9;
}

TEST(DynamicOptions, DumpLoadsBackIdentically)
{
	mrpt::config::CConfigFileMemory c(kGood);
	CDynamicKFSLAM2D f;
	f.loadOptions(c);
	std::ostringstream os;
	f.options.dumpToTextStream(os);
	std::string dumped = os.str();
	dumped = dumped.substr(dumped.find("measurement_model"));
	mrpt::config::CConfigFileMemory c2("[X]\n" + dumped);
	CDynamicKFSLAM2D::TOptions o2;
	o2.loadFromConfigFile(c2, "X");
	EXPECT_EQ(o2.Sigma_v, f.options.Sigma_v);
	EXPECT_EQ(o2.Sigma_0, f.options.Sigma_0);
	EXPECT_EQ(o2.Sigma_xi, f.options.Sigma_xi);
	EXPECT_EQ(o2.keep_last_poses, f.options.keep_last_poses);
	EXPECT_EQ(o2.measurement_model, f.options.measurement_model);
}
