/** TOptions: required keys, invalid values and the dump round trip. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
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

TEST(DynamicOptions, CompressedGoesWithTheOutlierMethodsEngine)
{
	// static_update = compressed and outlier_method = huber: the robust engine on the compressed
	// state (the lifecycle is its own seam; it used to be dropped silently in favour of huber).
	const std::string ini = replaced("keep_last_poses",
	                                 "keep_last_poses = 2\nstatic_update = compressed\n"
	                                 "outlier_method = huber");
	mrpt::config::CConfigFileMemory c(ini);
	CDynamicKFSLAM2D f;
	f.loadOptions(c);
	EXPECT_EQ(f.updateEngine().name(), "huber");
	EXPECT_EQ(f.stateLifecycle().name(), "compressed");
	CDynamicKFSLAM2D g;  // the default: the full state
	mrpt::config::CConfigFileMemory c2(kGood);
	g.loadOptions(c2);
	EXPECT_EQ(g.stateLifecycle().name(), "full");
}

TEST(DynamicOptions, CompressedEngineKnobs)
{
	// static_update = compressed: compressed_passive_after and compressed_batch reach the engine
	const std::string ini = replaced("keep_last_poses",
	                                 "keep_last_poses = 2\nstatic_update = "
	                                 "compressed\ncompressed_passive_after = "
	                                 "5\ncompressed_batch = 2");
	mrpt::config::CConfigFileMemory c(ini);
	CDynamicKFSLAM2D f;
	f.loadOptions(c);
	const auto* e = dynamic_cast<const estimator::CCompressedLifecycle*>(&f.stateLifecycle());
	ASSERT_NE(e, nullptr);
	EXPECT_EQ(f.updateEngine().name(), "sparse");
	EXPECT_EQ(e->passiveAfter(), 5);
	EXPECT_EQ(e->batch(), 2);
	// the dump loads back
	std::ostringstream os;
	f.options.dumpToTextStream(os);
	const std::string dumped = os.str();
	mrpt::config::CConfigFileMemory c2("[X]\n" + dumped.substr(dumped.find("measurement_model")));
	CDynamicKFSLAM2D::TOptions o2;
	o2.loadFromConfigFile(c2, "X");
	EXPECT_EQ(o2.compressed_passive_after, 5);
	EXPECT_EQ(o2.compressed_batch, 2);
	EXPECT_TRUE(o2.compressed_static_update);
	// defaults when absent
	CDynamicKFSLAM2D g;
	mrpt::config::CConfigFileMemory c3(kGood);
	g.loadOptions(c3);
	EXPECT_EQ(g.options.compressed_passive_after, 3);
	EXPECT_EQ(g.options.compressed_batch, 8);
	// invalid values: a clear error naming section, key and value
	const auto e1 =
	    loadError(replaced("keep_last_poses", "keep_last_poses = 2\ncompressed_batch = 0"));
	EXPECT_NE(e1.find("[DynamicKFSLAM] compressed_batch = 0: must be in [1, 1000000]"),
	          std::string::npos)
	    << e1;
	const auto e2 = loadError(
	    replaced("keep_last_poses", "keep_last_poses = 2\ncompressed_passive_after = -3"));
	EXPECT_NE(e2.find("[DynamicKFSLAM] compressed_passive_after = -3"), std::string::npos) << e2;
	const auto e3 = loadError(
	    replaced("keep_last_poses", "keep_last_poses = 2\ncompressed_passive_after = 2.5"));
	EXPECT_NE(e3.find("compressed_passive_after"), std::string::npos) << e3;
	EXPECT_NE(e3.find("not an integer"), std::string::npos) << e3;
	const auto e4 =
	    loadError(replaced("keep_last_poses", "keep_last_poses = 2\ncompressed_batch = many"));
	EXPECT_NE(e4.find("compressed_batch"), std::string::npos) << e4;
	EXPECT_NE(e4.find("not a number"), std::string::npos) << e4;
	const auto e5 =
	    loadError(replaced("keep_last_poses", "keep_last_poses = 2\ncompressed_batch = 1e10"));
	EXPECT_NE(e5.find("compressed_batch = 10000000000: must be in [1, 1000000]"), std::string::npos)
	    << e5;
	// an empty value
	const auto e6 =
	    loadError(replaced("keep_last_poses", "keep_last_poses = 2\ncompressed_batch ="));
	EXPECT_NE(e6.find("compressed_batch"), std::string::npos) << e6;
}
