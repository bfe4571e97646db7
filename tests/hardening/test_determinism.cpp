/** Determinism: the same rawlog, configuration and seed give bit-identical outputs, for the
 * simulator (serialized bytes) and the filter (mean and covariance after a full run, both
 * update paths), independent of what ran before in the process. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>

#include <cstring>

using namespace dynslam;

namespace
{
std::vector<uint8_t> serialize(const sim::TSimulatedRun& run)
{
	mrpt::io::CMemoryStream buf;
	auto ar = mrpt::serialization::archiveFrom(buf);
	for (size_t k = 0; k < run.actions.size(); ++k) ar << *run.actions[k] << *run.frames[k];
	const auto* p = static_cast<const uint8_t*>(buf.getRawBufferData());
	return std::vector<uint8_t>(p, p + buf.getTotalBytesCount());
}

struct TResult
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	size_t tracks = 0;
};

TResult runFilter(const std::vector<mrpt::obs::CActionCollection::Ptr>& acts,
                  const std::vector<mrpt::obs::CSensoryFrame::Ptr>& sfs,
                  const sim::TScenarioOptions& o, bool sparse)
{
	CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0 = o.Sigma_0;
	f.options.smoothing = true;
	f.options.keep_last_poses = 3;
	f.options.sparse_static_update = sparse;
	f.reset();
	for (size_t k = 0; k < acts.size(); ++k) f.processActionObservation(acts[k], sfs[k]);
	return {f.fullMean().asEigen(), f.fullCov().asEigen(), f.getObjectTracks().size()};
}

bool bitIdentical(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
	return a.rows() == b.rows() && a.cols() == b.cols() &&
	       std::memcmp(a.data(), b.data(), sizeof(double) * size_t(a.size())) == 0;
}

const char* kHighway = DYNSLAM_CONFIG_DIR "/highway.ini";
}  // namespace

TEST(Determinism, SimulatorSameSeedSameBytes)
{
	const auto o = sim::loadScenario(kHighway);
	const auto gt1 = sim::buildGroundTruth(o);
	const auto a = serialize(sim::simulateMeasurements(gt1, o, 5));
	// Something else in between (another seed, another scenario) must not change the result.
	(void)sim::simulateMeasurements(gt1, o, 6);
	(void)sim::simulateMeasurements(
	    sim::buildGroundTruth(
	        sim::loadScenario(DYNSLAM_CONFIG_DIR "/generated_small_scenario.ini")),
	    sim::loadScenario(DYNSLAM_CONFIG_DIR "/generated_small_scenario.ini"), 5);
	const auto gt2 = sim::buildGroundTruth(o);
	const auto b = serialize(sim::simulateMeasurements(gt2, o, 5));
	ASSERT_GT(a.size(), 10000u);
	EXPECT_EQ(a, b);
	// A different seed gives different bytes (the test can fail).
	EXPECT_NE(a, serialize(sim::simulateMeasurements(gt2, o, 6)));
}

TEST(Determinism, FilterSameRawlogSameState)
{
	mrpt::obs::CRawlog log;
	ASSERT_TRUE(log.loadFromRawLogFile(DYNSLAM_DATASETS_DIR "/highway.rawlog"));
	std::vector<mrpt::obs::CActionCollection::Ptr> acts;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> sfs;
	for (size_t i = 0; i + 1 < log.size(); ++i)
		if (log.getType(i) == mrpt::obs::CRawlog::etActionCollection &&
		    log.getType(i + 1) == mrpt::obs::CRawlog::etSensoryFrame)
		{
			acts.push_back(log.getAsAction(i));
			sfs.push_back(log.getAsObservations(i + 1));
			++i;
		}
	ASSERT_EQ(acts.size(), 121u);
	const auto o = sim::loadScenario(DYNSLAM_DATASETS_DIR "/highway_scenario.ini");
	for (bool sparse : {false, true})
	{
		const TResult r1 = runFilter(acts, sfs, o, sparse);
		const TResult other = runFilter(acts, sfs, o, !sparse);
		const TResult r2 = runFilter(acts, sfs, o, sparse);
		EXPECT_GT(r1.x.size(), 100) << "sparse " << sparse;
		EXPECT_GE(r1.tracks, 3u);
		EXPECT_TRUE(bitIdentical(r1.x, r2.x)) << "sparse " << sparse;
		EXPECT_TRUE(bitIdentical(r1.P, r2.P)) << "sparse " << sparse;
		// The two update paths agree only to rounding: the comparison is not vacuous.
		EXPECT_EQ(r1.x.size(), other.x.size());
		EXPECT_LT((r1.P - other.P).cwiseAbs().maxCoeff(), 1e-9 * r1.P.cwiseAbs().maxCoeff());
	}
}

TEST(Determinism, SimulateAndFilterEndToEnd)
{
	// Simulator output straight into the filter, twice from scratch: bit-identical states.
	const auto o = sim::loadScenario(DYNSLAM_CONFIG_DIR "/generated_small_scenario.ini");
	TResult r[2];
	for (int i = 0; i < 2; ++i)
	{
		const auto run = sim::simulateMeasurements(sim::buildGroundTruth(o), o, 3);
		r[i] = runFilter(run.actions, run.frames, o, true);
	}
	EXPECT_GT(r[0].x.size(), 20);
	EXPECT_TRUE(bitIdentical(r[0].x, r[1].x));
	EXPECT_TRUE(bitIdentical(r[0].P, r[1].P));
}
