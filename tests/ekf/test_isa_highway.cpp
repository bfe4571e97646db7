/** A whole highway run (datasets/highway.rawlog, 121 steps) with the AVX2/FMA kernels equals the
 * run with the SSE2 kernels (dynslam/core/kernels.h) within 1e-12 relative, mean and covariance,
 * with the sparse and the compressed update engines. Skipped (GTEST_SKIP) where the CPU lacks AVX2
 * or FMA or the build has no AVX2 variant. */
#include <dynslam/core/kernels.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include <iostream>

using namespace dynslam;
using kernels::Isa;

namespace
{
struct TEstimate
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	std::vector<std::string> labels;
};

TEstimate runHighway(Isa isa, bool compressed)
{
	mrpt::obs::CRawlog log;
	if (!log.loadFromRawLogFile(DYNSLAM_DATASETS_DIR "/highway.rawlog"))
		throw std::runtime_error("highway.rawlog");
	const auto o = sim::loadScenario(DYNSLAM_DATASETS_DIR "/highway_scenario.ini");
	kernels::CScopedIsa scoped(isa);
	CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0 = o.Sigma_0;
	f.options.compressed_static_update = compressed;
	f.reset();
	for (size_t i = 0; i + 1 < log.size(); ++i)
		if (log.getType(i) == mrpt::obs::CRawlog::etActionCollection &&
		    log.getType(i + 1) == mrpt::obs::CRawlog::etSensoryFrame)
		{
			f.processActionObservation(log.getAsAction(i), log.getAsObservations(i + 1));
			++i;
		}
	TEstimate e;
	f.getStateWithoutPads(e.x, e.P, &e.labels);  // the compressed filter's global update
	return e;
}

double relErr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
	return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

void compareIsas(bool compressed)
{
	if (!kernels::isaAvailable(Isa::Avx2))
		GTEST_SKIP() << "AVX2/FMA variant not available (compiled: "
		             << kernels::isaCompiled(Isa::Avx2)
		             << ", CPU has AVX2 and FMA: " << kernels::cpuSupports(Isa::Avx2) << ")";
	const TEstimate s = runHighway(Isa::Sse2, compressed), a = runHighway(Isa::Avx2, compressed);
	ASSERT_EQ(s.labels, a.labels);
	ASSERT_GT(s.x.size(), 150);
	const double ex = relErr(a.x, s.x), eP = relErr(a.P, s.P);
	EXPECT_LE(ex, 1e-12);
	EXPECT_LE(eP, 1e-12);
	std::cout << "[ measured ] highway, " << (compressed ? "compressed" : "sparse")
	          << " engine, AVX2 vs SSE2: mean " << ex << ", covariance " << eP << " (relative)\n";
}
}  // namespace

TEST(IsaHighway, Avx2RunEqualsSse2RunSparseEngine) { compareIsas(false); }
TEST(IsaHighway, Avx2RunEqualsSse2RunCompressedEngine) { compareIsas(true); }
