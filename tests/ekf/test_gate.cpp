/** Innovation gate: an outlier on a tracked landmark is rejected, counted, and the result
 * equals the run without that measurement; inliers pass untouched. Both update paths. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include "tiny_scenario.h"

using namespace dynslam;

namespace
{
mrpt::obs::CSensoryFrame::Ptr copyFrame(const mrpt::obs::CSensoryFrame::Ptr& sf, int dropIdx,
                                        float addRange)
{
	auto obs = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	auto o2 = mrpt::obs::CObservationBearingRange::Create(*obs);
	if (dropIdx >= 0)
	{
		if (addRange != 0)
			o2->sensedData[dropIdx].range += addRange;
		else
			o2->sensedData.erase(o2->sensedData.begin() + dropIdx);
	}
	auto out = mrpt::obs::CSensoryFrame::Create();
	out->insert(o2);
	return out;
}
}  // namespace

TEST(DynamicGate, OutlierRejectedAndEqualToRunWithoutIt)
{
	for (bool sparse : {false, true})
	{
		dynslam_test::TinyScenarioOptions o;
		o.steps = 25;
		o.objects = 1;
		const auto sc = dynslam_test::makeTinyScenario(o);
		CDynamicKFSLAM2D withOutlier, without, noGate;
		for (CDynamicKFSLAM2D* f : {&withOutlier, &without, &noGate})
		{
			f->options.measurement_model = models::MeasurementModel::RangeBearing;
			f->options.Sigma_v = o.Sigma_rb;
			f->options.sparse_static_update = sparse;
			f->options.innovation_gate = 0.999;
			f->reset();
		}
		noGate.options.innovation_gate = 0;
		size_t gated = 0, gatedClean = 0;
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			auto sf = sc.frames[k];
			if (k == 12)  // a 3 m range error on the first (already tracked) landmark seen now
			{
				withOutlier.processActionObservation(sc.actions[k], copyFrame(sf, 0, 3.0f));
				without.processActionObservation(sc.actions[k], copyFrame(sf, 0, 0.0f));
				noGate.processActionObservation(sc.actions[k], copyFrame(sf, 0, 3.0f));
				gated += withOutlier.getLastStepReport().gated_out;
				continue;
			}
			withOutlier.processActionObservation(sc.actions[k], sf);
			without.processActionObservation(sc.actions[k], sf);
			noGate.processActionObservation(sc.actions[k], sf);
			gatedClean += withOutlier.getLastStepReport().gated_out;
		}
		EXPECT_EQ(gated, 1u) << "sparse=" << sparse;
		EXPECT_EQ(gatedClean, 0u) << "no inlier of the clean data is gated (p = 0.999)";
		const Eigen::VectorXd a = withOutlier.fullMean().asEigen(),
		                      b = without.fullMean().asEigen();
		ASSERT_EQ(a.size(), b.size());
		EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12);
		// Without the gate the outlier pulls the ego away.
		const Eigen::VectorXd c = noGate.fullMean().asEigen();
		EXPECT_GT((c.head<2>() - b.head<2>()).norm(), 1e-3);
	}
}

TEST(DynamicGate, RejectsBadProbability)
{
	CDynamicKFSLAM2D::TOptions o;
	o.innovation_gate = 1.0;
	EXPECT_THROW(o.validate(), std::invalid_argument);
	o.innovation_gate = 0.99;
	EXPECT_NO_THROW(o.validate());
}
