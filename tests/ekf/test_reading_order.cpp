/** The order of the readings inside one observation does not change the estimate: the shipped
 * highway run (datasets/highway.rawlog, 121 steps, 3 cars) with every observation's readings
 * reversed equals the run in the recorded order, entry by entry under the state labels (the
 * state's order follows the readings', so entries are matched by label), to rounding. Catches
 * bookkeeping that assumes a reading order, e.g. an object's time-0 features looked up as if
 * they were created in ascending ID order (CDynamicKFSLAM2D_objects.cpp, indexObjects). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CRawlog.h>

#include <algorithm>
#include <cstdio>
#include <map>

using namespace dynslam;

namespace
{
struct TLabelled
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	std::map<std::string, Eigen::Index> at;  ///< label -> entry
};

TLabelled runHighway(bool reversed)
{
	mrpt::obs::CRawlog log;
	if (!log.loadFromRawLogFile(DYNSLAM_DATASETS_DIR "/highway.rawlog"))
		throw std::runtime_error("highway.rawlog");
	const auto o = sim::loadScenario(DYNSLAM_DATASETS_DIR "/highway_scenario.ini");
	CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0 = o.Sigma_0;
	f.reset();
	for (size_t i = 0; i + 1 < log.size(); ++i)
		if (log.getType(i) == mrpt::obs::CRawlog::etActionCollection &&
		    log.getType(i + 1) == mrpt::obs::CRawlog::etSensoryFrame)
		{
			auto sf = log.getAsObservations(i + 1);
			if (reversed)
				for (size_t k = 0; k < sf->size(); ++k)
					if (auto br =
					        sf->getObservationByIndexAs<mrpt::obs::CObservationBearingRange::Ptr>(
					            k))
						std::reverse(br->sensedData.begin(), br->sensedData.end());
			f.processActionObservation(log.getAsAction(i), sf);
			++i;
		}
	TLabelled e;
	std::vector<std::string> labels;
	f.getStateWithoutPads(e.x, e.P, &labels);
	for (size_t k = 0; k < labels.size(); ++k) e.at[labels[k]] = Eigen::Index(k);
	return e;
}
}  // namespace

TEST(ReadingOrder, ReversedReadingsGiveTheSameEstimate)
{
	const TLabelled a = runHighway(false), b = runHighway(true);
	ASSERT_EQ(a.at.size(), b.at.size());
	ASSERT_GT(a.x.size(), 100);  // ego, landmarks and the cars' features and poses
	double worstX = 0, worstP = 0;
	const double scaleP = a.P.cwiseAbs().maxCoeff();
	for (const auto& [label, i] : a.at)
	{
		const auto it = b.at.find(label);
		ASSERT_NE(it, b.at.end()) << label;
		worstX = std::max(worstX, std::abs(a.x(i) - b.x(it->second)));
		for (const auto& [label2, j] : a.at)
			worstP = std::max(worstP, std::abs(a.P(i, j) - b.P(it->second, b.at.at(label2))));
	}
	EXPECT_LT(worstX, 1e-10);           // measured 1.1e-13 m (rounding of the reordered rows)
	EXPECT_LT(worstP / scaleP, 1e-12);  // measured 1.3e-15
	char buf[96];
	std::snprintf(buf, sizeof buf, "mean %.3g, covariance %.3g relative", worstX, worstP / scaleP);
	RecordProperty("worst_difference", buf);
}
