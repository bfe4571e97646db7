/** The estimator core's bookkeeping (libs/estimator), pure Eigen: the ID-range router and the
 * object registry, the drop policy's exact rule, and the paper's smoothing as an object motion
 * model (Jacobians against numerical differentiation, the consecutive-steps rule). */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/constant_velocity.h>
#include <dynslam/estimator/drop_policy.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/estimator/state_layout.h>
#include <dynslam_test/numeric_jacobian.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
TReading rd(int32_t id) { return {id, Eigen::Vector2d(1, 2)}; }
}  // namespace

TEST(EstimatorRouter, IdRangeRoutesEveryKindAndOwnsTheRegistry)
{
	CIdRangeRouter r;
	const int32_t a0 = ids::objectFeatureId(0, 0), a1 = ids::objectFeatureId(0, 1),
	              a2 = ids::objectFeatureId(0, 2);
	auto known = [](int32_t id) { return id == 5; };
	// Step 0: object 0 first seen with features 0 and 1.
	TRoutedStep s0 = r.route(0, {rd(5), rd(a0), rd(7), rd(a1)}, known);
	ASSERT_EQ(s0.readings.size(), 4u);
	EXPECT_EQ(s0.readings[0].route, Route::StaticKnown);
	EXPECT_EQ(s0.readings[1].route, Route::ObjectFirstSighting);
	EXPECT_EQ(s0.readings[2].route, Route::StaticNew);
	EXPECT_EQ(s0.readings[3].route, Route::ObjectFirstSighting);
	EXPECT_EQ(s0.readings[3].object, 0);
	EXPECT_EQ(s0.readings[3].feature, 1);
	EXPECT_EQ(s0.statics().size(), 2u);
	EXPECT_EQ(s0.objects().size(), 2u);
	EXPECT_EQ(r.registry().at(0).first_step, 0);
	EXPECT_EQ(r.registry().at(0).feature_ids, (std::vector<int32_t>{a0, a1}));
	EXPECT_EQ(r.registry().at(0).feature_index, (std::vector<int32_t>{0, 1}));
	EXPECT_EQ(r.registry().at(0).poseDim(), 3);
	// Step 1: feature 1 again (time t), feature 2 unknown (no f_0): skipped and counted.
	TRoutedStep s1 = r.route(1, {rd(a1), rd(a2)}, known);
	EXPECT_EQ(s1.readings[0].route, Route::ObjectTimeT);
	EXPECT_EQ(s1.readings[1].route, Route::Skip);
	EXPECT_EQ(s1.skipped_unknown_object_feature, 1u);
	EXPECT_EQ(s1.objects().size(), 1u);
	EXPECT_TRUE(r.registry().isTimeT(0, 1));
	EXPECT_FALSE(r.registry().isTimeT(0, 0));
	EXPECT_EQ(r.registry().at(0).feature_ids.size(), 2u);  // the unknown one was not added
	EXPECT_EQ(r.featureId(0, 1), a1);
	r.reset();
	EXPECT_FALSE(r.registry().has(0));
}

TEST(EstimatorRouter, IdRangeValidationNamesTheReading)
{
	CIdRangeRouter r;
	EXPECT_NO_THROW(r.validate({rd(1), rd(ids::objectFeatureId(3, 0))}, "who"));
	// -1 is MRPT's unknown landmark: accepted (associated in route(), issue 30); -7 is in no
	// range.
	EXPECT_NO_THROW(r.validate({rd(1), rd(-1), rd(-1)}, "who"));
	try
	{
		r.validate({rd(1), rd(-7)}, "who");
		FAIL() << "-7 accepted";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("who: measurement 1 (landmark ID -7)"),
		          std::string::npos)
		    << e.what();
	}
	EXPECT_THROW(r.validate({rd(4), rd(4)}, "who"), std::runtime_error);
	EXPECT_THROW(makeRouter("classify-not-yet"), std::invalid_argument);
	EXPECT_EQ(makeRouter("ids")->name(), "ids");
}

TEST(EstimatorDropPolicy, StaticLandmarkDroppedExactlyNStepsAfterItsLastReading)
{
	TDropOptions o;
	o.drop_static_after_unseen_steps = 3;
	CDropPolicy d(o);
	d.noteSeen(7, 10);
	EXPECT_FALSE(d.staticDue(7, 10, 10));
	EXPECT_FALSE(d.staticDue(7, 12, 10));
	EXPECT_TRUE(d.staticDue(7, 13, 10));  // 13 - 10 = N
	d.noteSeen(7, 13);
	EXPECT_FALSE(d.staticDue(7, 13, 10));
	// Never noted: its step of addition stands in.
	EXPECT_FALSE(d.staticDue(8, 4, 2));
	EXPECT_TRUE(d.staticDue(8, 5, 2));
	d.forget(7);
	EXPECT_TRUE(d.staticDue(7, 13, 10));
	// N = 0: never.
	EXPECT_FALSE(CDropPolicy(TDropOptions{}).staticDue(7, 1000, 0));
}

TEST(EstimatorDropPolicy, KeepsTheLastKPoses)
{
	TDropOptions o;
	o.keep_last_poses = 3;
	const CDropPolicy d(o);
	EXPECT_EQ(d.posesToDrop(0), 0u);
	EXPECT_EQ(d.posesToDrop(3), 0u);
	EXPECT_EQ(d.posesToDrop(4), 1u);
	EXPECT_EQ(d.posesToDrop(10), 7u);
}

TEST(EstimatorMotionModel, SmoothingNeedsThreeConsecutiveStepsEndingNow)
{
	const CPaperSmoothing m(Eigen::Matrix3d::Identity() * 0.01);
	EXPECT_EQ(m.select(2, 10, {8, 9, 10}, 3).size(), 1u);
	EXPECT_EQ(m.select(2, 10, {7, 8, 9, 10}, 3).size(), 1u);
	EXPECT_TRUE(m.select(2, 10, {7, 9, 10}, 3).empty());  // unseen at step 8: a gap
	EXPECT_TRUE(m.select(2, 10, {8, 9}, 3).empty());      // not seen now
	EXPECT_TRUE(m.select(2, 10, {7, 8, 10}, 3).empty());
	const auto pm = m.select(4, 5, {3, 4, 5}, 2);
	ASSERT_EQ(pm.size(), 1u);
	EXPECT_EQ(pm[0].object, 4);
	EXPECT_EQ(pm[0].steps, (std::vector<int>{3, 4, 5}));
	EXPECT_EQ(pm[0].R.rows(), 2);
	EXPECT_TRUE(CNoObjectMotion().select(2, 10, {8, 9, 10}, 3).empty());
}

TEST(EstimatorMotionModel, SmoothingJacobiansMatchNumericalAcrossPi)
{
	const CPaperSmoothing m(Eigen::Matrix3d::Identity());
	TPseudoMeasurement pm;
	pm.steps = {0, 1, 2};
	pm.dim = 3;
	for (const double th : {0.3, M_PI - 1e-3, -M_PI + 1e-3})
	{
		Eigen::VectorXd all(9);
		// Angles given wrapped, so near +-pi the differences cross the cut.
		all << 1, 2, th, 1.2, 2.1, models::wrapToPi(th + 2e-3), 1.5, 2.3,
		    models::wrapToPi(th + 5e-3);
		auto f = [&](const Eigen::VectorXd& v) {
			return m.residual(pm, {v.segment(0, 3), v.segment(3, 3), v.segment(6, 3)}, nullptr);
		};
		std::vector<Eigen::MatrixXd> J;
		const Eigen::VectorXd r =
		    m.residual(pm, {all.segment(0, 3), all.segment(3, 3), all.segment(6, 3)}, &J);
		ASSERT_EQ(J.size(), 3u);
		Eigen::MatrixXd Jall(3, 9);
		Jall << J[0], J[1], J[2];
		EXPECT_TRUE(dynslam_test::jacobianMatches(Jall, f, all, 1e-6));
		EXPECT_NEAR(r[2], 1e-3, 1e-12) << "angle differences wrapped at theta = " << th;
	}
}

TEST(EstimatorLayout, TypedBlocksMapToPaddedSlots)
{
	CPaddedLayout L;
	TBlock lm;
	lm.id = 4;
	TBlock pose;
	pose.kind = BlockKind::ObjectPose;
	pose.object = 1;
	pose.dim = 3;
	TBlock pose2 = pose;
	pose2.dim = 2;  // translation-only: no pad
	L.append(lm);
	L.append(pose);
	L.append(pose2);
	L.append(lm);
	EXPECT_EQ(L.storageDim(), 3 + 2 + 4 + 2 + 2);
	EXPECT_EQ(L.first(0), 3);
	EXPECT_EQ(L.first(1), 5);
	EXPECT_EQ(L.first(2), 9);
	EXPECT_EQ(L.first(3), 11);
	EXPECT_EQ(L.indices(1), (std::vector<int>{5, 6, 7}));
	EXPECT_EQ(L.padIndices(), (std::vector<int>{8}));
	EXPECT_EQ(L.numSlots(), 5u);
	EXPECT_EQ(L.slotOf(2), 3u);
	EXPECT_EQ(L.blockAtSlot(2), 1u);  // the pose's second slot [dtheta, pad]
	const std::vector<bool> drop{false, true, false, false};
	EXPECT_EQ(L.keptStorage(drop), (std::vector<int>{0, 1, 2, 3, 4, 9, 10, 11, 12}));
	L.removeBlocks(drop);
	ASSERT_EQ(L.size(), 3u);
	EXPECT_EQ(L.first(1), 5);
	EXPECT_EQ(L[1].dim, 2);
	EXPECT_TRUE(L.padIndices().empty());
	TBlock bad;
	bad.dim = 7;  // 1..6: the velocity block of ca, [v; a], has 6 entries (3 slots)
	EXPECT_THROW(L.append(bad), std::invalid_argument);
	bad.dim = 0;
	EXPECT_THROW(L.append(bad), std::invalid_argument);
	TBlock va;
	va.kind = BlockKind::ObjectVelocity;
	va.dim = 6;
	L.append(va);
	EXPECT_EQ(L.indices(3).size(), 6u);
	EXPECT_EQ(L.numSlots(), 6u);  // 2 + 1 + 3, no pad
	EXPECT_TRUE(L.padIndices().empty());
	EXPECT_THROW(L.keptStorage({true}), std::invalid_argument);
}

TEST(EstimatorMotionModel, ConstantVelocityPredictsWithItsProcessNoise)
{
	using dynslam::estimator::CConstantVelocity;
	using dynslam::estimator::TCvParams;
	TCvParams p;
	p.dt = 0.5;
	p.accel_psd = Eigen::Vector3d(0.2, 0.3, 0.01);
	p.velocity_prior_std = Eigen::Vector3d(0.5, 0.6, 0.05);
	const CConstantVelocity cv(p);
	EXPECT_EQ(cv.velocityDim(3), 3);
	EXPECT_EQ(cv.velocityDim(2), 2);
	Eigen::VectorXd s(6);
	s << 1, 2, 3.1, 4, 5, 0.2;
	Eigen::MatrixXd F, Q;
	const Eigen::VectorXd out = cv.predict(s, &F, &Q);
	EXPECT_NEAR(out[0], 1 + 0.5 * 4, 1e-15);
	EXPECT_NEAR(out[2], dynslam::models::wrapToPi(3.1 + 0.1), 1e-15);
	Eigen::MatrixXd Fexp;
	dynslam::models::cvPredict(s, 0.5, &Fexp);
	EXPECT_EQ(F, Fexp);
	// Q is the white-acceleration noise of the parameters (not zero, not the identity).
	EXPECT_TRUE(Q.isApprox(dynslam::models::cvProcessNoise(p.accel_psd, 0.5)));
	EXPECT_GT(Q(3, 3), 0.0);
	Eigen::MatrixXd J, Sigma;
	const Eigen::VectorXd v = cv.initialVelocity(Eigen::Vector2d(1, 2), 2, &J, &Sigma);
	EXPECT_TRUE(v.isApprox(Eigen::Vector2d(1, 2) / 1.0));
	EXPECT_TRUE(Sigma.isApprox(Eigen::Vector2d(0.25, 0.36).asDiagonal().toDenseMatrix()));
	EXPECT_THROW(cv.initialVelocity(Eigen::Vector2d(1, 2), 0, &J, &Sigma), std::invalid_argument);
	TCvParams bad = p;
	bad.velocity_prior_std[1] = 0;  // not positive definite
	EXPECT_THROW(CConstantVelocity{bad}, std::invalid_argument);
	bad = p;
	bad.dt = 0;
	EXPECT_THROW(CConstantVelocity{bad}, std::invalid_argument);
}
