/** object_model = cv (issue 13): the heading inflation of object readings
 * (cv_heading_inflation, doc/state-layout.md "Heading inflation of object readings"). With a
 * large prior heading variance (Sigma_0 = Sigma_w, as in the paper's Table I), precise readings
 * and large odometry noise, steady objects pull the ego away from the truth (doc/results/results.md
 * 4.3.2); the inflation limits that. Off, the filter is today's to the last digit. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <sstream>

#include "highway_cv_setup.h"
#include "object_model_setup.h"

using namespace dynslam;

namespace
{
/** cv (heading inflation c) or the paper's model, with the level's noise and prior. */
void configure(CDynamicKFSLAM2D& f, const sim::TScenarioOptions& o, const std::string& model,
               double c)
{
	dynslam_test::configureHighwayCv(f, o, model, Eigen::Vector3d(1e-5, 1e-5, 1e-7));
	f.options.cv_gate = 0.5;
	f.options.cv.heading_inflation = c;
	f.reset();
}

}  // namespace

TEST(ObjectModelCvHeading, ReadingsTellTheEgoHeadingLessAsTheInflationGrows)
{
	// The same highway data (w3v1, one seeded run, Sigma_0 = 0: the heading variance is the
	// odometry's) through filters that differ only in c: up to the first step with object updates
	// they are equal bit for bit (c = 0 also to the filter whose key was never set); over the
	// first 12 steps of object updates, the ego heading variance after the step grows with c
	// (the readings carry less information on it).
	sim::TScenarioOptions o = dynslam_test::highwayW3v1();
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun run = sim::simulateMeasurements(gt, o, 9000);
	o.Sigma_0.setZero();
	const std::vector<double> cs{0, 3, 100};
	std::vector<CDynamicKFSLAM2D> f(cs.size());
	for (size_t i = 0; i < cs.size(); ++i) configure(f[i], o, "cv", cs[i]);
	CDynamicKFSLAM2D unset;  // the key never set: its default
	configure(unset, o, "cv", 0);
	unset.options.cv = estimator::TCvParams();
	unset.options.cv.dt = o.dt;
	unset.options.cv.accel_psd = f[0].options.cv.accel_psd;
	unset.options.cv.velocity_prior_std = f[0].options.cv.velocity_prior_std;
	unset.reset();
	int withUpdates = 0;
	std::vector<double> sum(cs.size(), 0.0);
	for (size_t k = 0; k < run.actions.size() && withUpdates < 12; ++k)
	{
		for (auto& x : f) x.processActionObservation(run.actions[k], run.frames[k]);
		unset.processActionObservation(run.actions[k], run.frames[k]);
		EXPECT_EQ(dynslam_test::meanAndCovariance(f[0]), dynslam_test::meanAndCovariance(unset))
		    << "c = 0 is the default, step " << k;
		if (f[0].getLastStepReport().object_feature_updates == 0)
		{
			for (size_t i = 1; i < cs.size() && withUpdates == 0; ++i)
				ASSERT_EQ(dynslam_test::meanAndCovariance(f[i]),
				          dynslam_test::meanAndCovariance(f[0]))
				    << "step " << k;
			continue;
		}
		++withUpdates;
		for (size_t i = 0; i < cs.size(); ++i) sum[i] += std::sqrt(f[i].getEgoPose().cov(2, 2));
	}
	ASSERT_EQ(withUpdates, 12);
	std::printf("[ measured ] mean ego heading std over 12 steps with object updates [rad]:");
	for (size_t i = 0; i < cs.size(); ++i)
	{
		std::printf(" c = %g: %.6g", cs[i], sum[i] / 12);
		if (i > 0)
		{
			EXPECT_GT(sum[i], sum[i - 1] * (1 + 3e-4)) << "c = " << cs[i];
		}
	}
	std::printf("\n");
}

TEST(ObjectModelCvHeading, OptionsDumpAndBadInput)
{
	dynslam_test::expectScalarCvKey(&estimator::TCvParams::heading_inflation,
	                                "cv_heading_inflation", 3, "3");
}

TEST(ObjectModelCvHeading, TheGateIgnoresTheInflation)
{
	// The gate tests each object reading with S = H P H^T + Sigma_v whatever c is
	// (doc/state-layout.md "Heading inflation of object readings": the inflation throttles what
	// a reading tells the ego, it is not the reading's noise). A poorly known ego heading (prior
	// variance 1e-2 rad^2) and, at the first step with object updates, every object reading
	// 0.15 rad off in bearing: NIS about 0.15^2 / 1e-2 = 2.3 > the gate 1.39 (cv_gate = 0.5).
	// Two filters that differ only in c (0 and 100) are equal bit for bit before that update,
	// so they gate out the same readings; with S + c P_thth h h^T in the gate, c = 100 would
	// keep some (measured with that change: 8 gated out at c = 0, 4 at c = 100).
	sim::TScenarioOptions o = dynslam_test::highwayW3v1();
	o.Sigma_0.diagonal() << 1e-4, 1e-4, 1e-2;
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	sim::TSimulatedRun run = sim::simulateMeasurements(gt, o, 9000);
	CDynamicKFSLAM2D probe, off, on;
	configure(probe, o, "cv", 0);
	size_t first = 0;  // the first step with object updates
	for (; first < run.actions.size(); ++first)
	{
		probe.processActionObservation(run.actions[first], run.frames[first]);
		if (probe.getLastStepReport().object_feature_updates > 0) break;
	}
	ASSERT_LT(first, run.actions.size());
	auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
	    *run.frames[first]->getObservationByClass<mrpt::obs::CObservationBearingRange>());
	for (auto& m : obs->sensedData)
		if (!ids::isStatic(m.landmarkID)) m.yaw += 0.15f;
	run.frames[first] = mrpt::obs::CSensoryFrame::Create();
	run.frames[first]->insert(obs);
	configure(off, o, "cv", 0);
	configure(on, o, "cv", 100);
	for (size_t k = 0; k <= first; ++k)
	{
		off.processActionObservation(run.actions[k], run.frames[k]);
		on.processActionObservation(run.actions[k], run.frames[k]);
	}
	const TStepReport &a = off.getLastStepReport(), &b = on.getLastStepReport();
	std::printf("[ measured ] step %zu: gated out %zu (c = 0), %zu (c = 100); updates %zu, %zu\n",
	            first, a.object_gated_out, b.object_gated_out, a.object_feature_updates,
	            b.object_feature_updates);
	EXPECT_GT(a.object_gated_out, 0u);
	EXPECT_EQ(b.object_gated_out, a.object_gated_out);
	EXPECT_EQ(b.object_feature_updates, a.object_feature_updates);
}
