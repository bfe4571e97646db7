/** The state's lifecycle composes with every update engine (issue 32): static_update =
 * compressed with each outlier method equals the uncompressed filter with the same method, to
 * 1e-9 in mean and covariance, on a run where no landmark goes passive and on a run with
 * revisits where landmarks do go passive (and are read again: global updates). Before the
 * lifecycle was a seam of its own, compressed with huber, cauchy, gate_recovery or jcbb
 * silently ran uncompressed (the passive count stayed 0). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/ekf/CMrptUpdateEngine.h>
#include <gtest/gtest.h>

#include "compressed_runs.h"

using namespace dynslam;

namespace
{
using namespace compressed_runs;

void configure(CDynamicKFSLAM2D& f, const TSteps& s, const std::string& method, bool compressed,
               int batch)
{
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = s.Sigma_v;
	f.options.Sigma_0 = s.Sigma_0;
	f.options.outlier_method = method;
	f.options.innovation_gate = 0.999;  // the gate of gate, gate_recovery and jcbb
	f.options.compressed_static_update = compressed;
	f.options.compressed_batch = batch;
	f.options.validate();
	f.reset();
}

/** Runs a full and a compressed filter with `method` over s; returns the most passive
 * landmarks seen at the end of a step and compares the estimates at the end. */
size_t runBoth(const TSteps& s, const std::string& method, int batch, const std::string& what)
{
	CDynamicKFSLAM2D full, comp;
	configure(full, s, method, false, batch);
	configure(comp, s, method, true, batch);
	EXPECT_EQ(comp.updateEngine().name(), full.updateEngine().name()) << what;
	EXPECT_EQ(comp.stateLifecycle().name(), "compressed") << what;
	EXPECT_EQ(full.stateLifecycle().name(), "full") << what;
	size_t maxPassive = 0;
	for (size_t k = 0; k < s.acts.size(); ++k)
	{
		full.processActionObservation(s.acts[k], s.sfs[k]);
		comp.processActionObservation(s.acts[k], s.sfs[k]);
		maxPassive = std::max(maxPassive, comp.passiveLandmarks());
	}
	const auto e = compare(full, comp, what + " (expanded copy)");
	comp.globalUpdate();
	const auto g = compare(full, comp, what + " (after the global update)");
	std::cout << what << ": most passive landmarks " << maxPassive << ", relative error mean "
	          << std::max(e.first, g.first) << ", covariance " << std::max(e.second, g.second)
	          << "\n";
	return maxPassive;
}

class CompressedWithEveryOutlierMethod : public ::testing::TestWithParam<const char*>
{
};
}  // namespace

TEST_P(CompressedWithEveryOutlierMethod, NoLandmarkPassiveEqualsUncompressed)
{
	static const TSteps s = generated();
	// A batch larger than the map: nothing is ever compressed.
	EXPECT_EQ(runBoth(s, GetParam(), 1000000, std::string("generated/") + GetParam()), 0u);
}

TEST_P(CompressedWithEveryOutlierMethod, CompressesAndEqualsUncompressed)
{
	static const TSteps s = ring();
	EXPECT_GT(runBoth(s, GetParam(), 8, std::string("ring/") + GetParam()), 0u);
}

INSTANTIATE_TEST_SUITE_P(OutlierMethods, CompressedWithEveryOutlierMethod,
                         ::testing::Values("gate", "none", "huber", "cauchy", "gate_recovery",
                                           "jcbb"));

TEST(StateLifecycle, BadParametersAndMrptsEngineAreClearErrors)
{
	EXPECT_THROW(estimator::CCompressedLifecycle(0, 8), std::invalid_argument);
	EXPECT_THROW(estimator::CCompressedLifecycle(3, 0), std::invalid_argument);
	EXPECT_NO_THROW(estimator::CCompressedLifecycle(1, 1));
	// MRPT's update works on the filter's own storage: no compressed lifecycle with it.
	CDynamicKFSLAM2D f;
	f.options.sparse_static_update = false;  // static_update = mrpt
	f.setStateLifecycle(std::make_unique<estimator::CCompressedLifecycle>());
	try
	{
		f.reset();
		ADD_FAILURE() << "mrpt engine with a compressed lifecycle accepted";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("compressed"), std::string::npos) << e.what();
		EXPECT_NE(std::string(e.what()).find("mrpt"), std::string::npos) << e.what();
	}
	// The full lifecycle goes with it.
	f.setStateLifecycle(std::make_unique<estimator::CFullStateLifecycle>());
	EXPECT_NO_THROW(f.reset());
	EXPECT_EQ(f.updateEngine().name(), "mrpt");
}
