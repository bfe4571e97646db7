/** object_model = cv (issue 13): the constant-velocity object model in the dynamic EKF.
 * Invariants with velocity blocks, objects that help the ego where static landmarks are
 * scarce, a seeded Monte Carlo NEES check, the gate on object readings, options. */
#include <dynslam/core/models/object_pose.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/eval/chi2.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Eigenvalues>

#include "object_model_setup.h"
#include "tiny_scenario.h"

using namespace dynslam;
using dynslam_test::TinyScenarioOptions;

namespace
{
TinyScenarioOptions cvScenario(unsigned seed, int landmarks, double turn)
{
	TinyScenarioOptions o;
	o.seed = seed;
	o.objects = 2;
	o.features_per_object = 3;
	o.landmarks = landmarks;
	o.cartesian_noise = true;
	o.steps = 40;
	o.object_turn_rate = turn;
	return o;
}

/** The filter for the tiny scenario (one step = 1 s): cv or the paper's model. */
void configure(CDynamicKFSLAM2D& f, const TinyScenarioOptions& o, bool cv)
{
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0.setZero();
	f.options.Sigma_xi = Eigen::Matrix2d::Identity() * 1e-6;
	f.options.object_model = cv ? "cv" : "paper";
	f.options.cv.dt = 1.0;
	f.options.cv.accel_psd = Eigen::Vector3d(1e-9, 1e-9, 1e-11);
	f.options.cv.velocity_prior_std = Eigen::Vector3d(1e-4, 1e-4, 1e-5);
	f.reset();
}

/** The true objects of makeTinyScenario(o) (same draws). */
std::vector<dynslam_test::TinyObject> trueObjects(const TinyScenarioOptions& o)
{
	std::mt19937 g(o.seed);
	std::uniform_real_distribution<double> U(-14, 14);
	for (int i = 0; i < 2 * o.landmarks; ++i) U(g);
	return dynslam_test::makeTinyObjects(o, g, U);
}

Eigen::Matrix2Xd trueFeatures(const dynslam_test::TinyObject& ob, int k)
{
	Eigen::Matrix2Xd F(2, ob.off.cols());
	for (int i = 0; i < ob.off.cols(); ++i)
		F.col(i) = ob.c + ob.v * k + models::rot2(ob.w * k) * ob.off.col(i);
	return F;
}

double egoError(const CDynamicKFSLAM2D& f, const Eigen::Vector3d& truth)
{
	const auto p = f.getEgoPose().mean;
	return std::hypot(p.x() - truth[0], p.y() - truth[1]);
}

double egoNees(const CDynamicKFSLAM2D& f, const Eigen::Vector3d& truth)
{
	const auto p = f.getEgoPose();
	Eigen::Vector3d e(p.mean.x() - truth[0], p.mean.y() - truth[1],
	                  models::wrapToPi(p.mean.phi() - truth[2]));
	return e.dot(p.cov.asEigen().ldlt().solve(e));
}
}  // namespace

TEST(ObjectModelCv, InvariantsAndVelocityBlocks)
{
	for (const int nf : {1, 3})
	{
		TinyScenarioOptions o = cvScenario(3, 6, 0.03);
		o.features_per_object = nf;
		const auto sc = dynslam_test::makeTinyScenario(o);
		CDynamicKFSLAM2D f;
		configure(f, o, true);
		size_t updates = 0;
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			f.processActionObservation(sc.actions[k], sc.frames[k]);
			updates += f.getLastStepReport().object_feature_updates;
			const Eigen::MatrixXd P = f.fullCov().asEigen();
			EXPECT_LE((P - P.transpose()).cwiseAbs().maxCoeff(), 1e-12);
			EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues().minCoeff(),
			          -1e-10);
			for (const size_t i : f.padIndices())
			{
				EXPECT_EQ(P(i, i), 1.0);
				EXPECT_EQ((P.row(i).array() != 0).count(), 1) << "pad correlated, step " << k;
			}
		}
		// Every object seen twice has a pose and a velocity of the pose's size, and no time-t
		// feature stays in the state.
		int velocities = 0;
		for (const auto& b : f.getLayout().blocks())
		{
			EXPECT_NE(b.kind, estimator::BlockKind::ObjectFeatureT);
			if (b.kind == estimator::BlockKind::ObjectVelocity)
			{
				++velocities;
				EXPECT_EQ(b.dim, nf == 1 ? 2 : 3);
			}
		}
		EXPECT_EQ(velocities, 2) << nf << " features";
		EXPECT_GT(updates, 40u);
		// One pose per step in the tracks from the object's first pose on.
		for (const auto& [obj, tr] : f.getObjectTracks())
		{
			ASSERT_FALSE(tr.poses.empty());
			EXPECT_EQ(tr.poses.back().step, int(sc.actions.size()) - 1);
			for (size_t i = 1; i < tr.poses.size(); ++i)
				EXPECT_EQ(tr.poses[i].step, tr.poses[i - 1].step + 1);
		}
	}
}

TEST(ObjectModelCv, ObjectsHelpTheEgoWithoutStaticLandmarks)
{
	// No static landmark at all: the paper's filter is dead reckoning (its objects never update
	// the ego); with cv, two objects translating steadily bound the ego's random walk.
	double sumPaper = 0, sumCv = 0;
	const int runs = 20;
	for (int r = 0; r < runs; ++r)
	{
		const TinyScenarioOptions o = cvScenario(100 + unsigned(r), 0, 0.0);
		const auto sc = dynslam_test::makeTinyScenario(o);
		CDynamicKFSLAM2D paper, cv;
		configure(paper, o, false);
		configure(cv, o, true);
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			paper.processActionObservation(sc.actions[k], sc.frames[k]);
			cv.processActionObservation(sc.actions[k], sc.frames[k]);
		}
		sumPaper += egoError(paper, sc.ego.back());
		sumCv += egoError(cv, sc.ego.back());
	}
	std::printf("[ measured ] final ego position error, mean of %d runs: paper %.4f m, cv %.4f m\n",
	            runs, sumPaper / runs, sumCv / runs);
	// Measured: paper 0.0986 m, cv 0.0800 m (ratio 0.81). The linear part of the ego's drift is
	// unobservable from objects of unknown constant velocity (Galilean invariance), so the gain
	// is limited without any static landmark.
	EXPECT_LT(sumCv, 0.95 * sumPaper);
}

TEST(ObjectModelCv, MonteCarloNeesOfEgoAndObjectPoses)
{
	// Objects translating at constant velocity, few static landmarks. The filter's model matches
	// the truth (zero acceleration: process noise and velocity prior near zero). Measured: ego
	// 3.08 in [2.19, 3.94], object poses 6.17 in [4.83, 7.30]. With accel_psd = (1e-6, 1e-6,
	// 1e-8) and velocity_prior_std = (0.01, 0.01, 0.001), larger than the truth's, the filter is
	// conservative: ego 2.10, object poses 4.39 (below the lower bounds).
	const int runs = 30;
	double egoSum = 0, objSum = 0, paperSum = 0;
	int objDof = 0;
	for (int r = 0; r < runs; ++r)
	{
		const TinyScenarioOptions o = cvScenario(200 + unsigned(r), 3, 0.0);
		const auto sc = dynslam_test::makeTinyScenario(o);
		CDynamicKFSLAM2D f, paper;
		configure(f, o, true);
		configure(paper, o, false);
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			f.processActionObservation(sc.actions[k], sc.frames[k]);
			paper.processActionObservation(sc.actions[k], sc.frames[k]);
		}
		const int last = int(sc.actions.size()) - 1;
		egoSum += egoNees(f, sc.ego.back());
		paperSum += egoNees(paper, sc.ego.back());
		const auto objs = trueObjects(o);
		for (const auto& [obj, tr] : f.getObjectTracks())
		{
			const auto& p = tr.poses.back();
			ASSERT_EQ(p.step, last);
			const int t0 = f.router().registry().at(obj).first_step;
			const Eigen::Vector3d xi = models::objectPoseInverse(
			    trueFeatures(objs[size_t(obj)], t0), trueFeatures(objs[size_t(obj)], last));
			Eigen::VectorXd e = p.mean - xi.head(p.mean.size());
			if (e.size() == 3) e[2] = models::wrapToPi(e[2]);
			objSum += e.dot(p.cov.ldlt().solve(e));
			objDof += int(e.size());
		}
	}
	const auto egoB = eval::averageChi2Bounds(3.0 * runs, runs);
	const auto objB = eval::averageChi2Bounds(objDof, runs);
	std::printf(
	    "[ measured ] average NEES over %d runs: ego %.3f [%.3f, %.3f], object poses %.3f "
	    "[%.3f, %.3f] (%d dof)\n",
	    runs, egoSum / runs, egoB.lower, egoB.upper, objSum / runs, objB.lower, objB.upper, objDof);
	std::printf("[ measured ] the paper's filter on the same runs: ego NEES %.3f\n",
	            paperSum / runs);
	EXPECT_TRUE(egoB.contains(egoSum / runs));
	EXPECT_TRUE(objB.contains(objSum / runs));
}

TEST(ObjectModelCv, GateRejectsAJumpingObject)
{
	// Object 0 jumps by 3 m at step 25 (a misclassified or braking object): without the gate its
	// readings drag the ego; with cv_gate they are rejected and counted.
	const TinyScenarioOptions o = cvScenario(7, 3, 0.0);
	auto sc = dynslam_test::makeTinyScenario(o);
	for (size_t k = 25; k < sc.frames.size(); ++k)
	{
		auto obs = sc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		for (auto& m : obs->sensedData)
			if (m.landmarkID >= ids::objectFeatureId(0, 0) &&
			    m.landmarkID < ids::objectFeatureId(1, 0))
				m.range += 3.0f;
	}
	double err[2];
	size_t gated[2];
	for (const bool gate : {false, true})
	{
		CDynamicKFSLAM2D f;
		configure(f, o, true);
		f.options.cv_gate = gate ? 0.999 : 0.0;
		f.reset();
		gated[gate] = 0;
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			f.processActionObservation(sc.actions[k], sc.frames[k]);
			gated[gate] += f.getLastStepReport().object_gated_out;
		}
		err[gate] = egoError(f, sc.ego.back());
	}
	std::printf(
	    "[ measured ] ego error with a jumping object: no gate %.4f m, gate %.4f m "
	    "(%zu readings gated)\n",
	    err[0], err[1], gated[1]);
	EXPECT_EQ(gated[0], 0u);
	EXPECT_GT(gated[1], 10u);
	EXPECT_LT(err[1], 0.5 * err[0]);
}

TEST(ObjectModelCv, OptionsAndBadInput)
{
	const auto load = [](const std::string& extra)
	{ return dynslam_test::loadCartesianFilter(extra)->objectMotionModel().name(); };
	EXPECT_EQ(load(""), "none");
	EXPECT_EQ(load("object_model = paper\n"), "none");
	EXPECT_EQ(load("object_model = paper_smoothing\nkeep_last_poses = 3\nSigma_s = [1 1 1]\n"),
	          "paper_smoothing");
	EXPECT_EQ(load("object_model = cv\n[ObjectModel]\ncv_dt = 0.5\n"), "cv");
	EXPECT_THROW(load("object_model = cv\n"), std::exception);  // cv_dt is required
	EXPECT_THROW(load("object_model = ctra\n[ObjectModel]\ncv_dt = 0.5\n"),
	             std::invalid_argument);  // unknown
	EXPECT_THROW(load("object_model = cv\n[ObjectModel]\ncv_dt = 0.5\n[DynamicKFSLAM]\nsmoothing = "
	                  "true\nkeep_last_poses = 3\n"),
	             std::invalid_argument);
	EXPECT_THROW(
	    load("object_model = cv\n[ObjectModel]\ncv_dt = 0.5\ncv_velocity_prior_std = [1 0 1]\n"),
	    std::invalid_argument);
	EXPECT_THROW(load("object_model = cv\n[ObjectModel]\ncv_dt = 0.5\ncv_accel_psd = [1 -1 1]\n"),
	             std::invalid_argument);
	EXPECT_THROW(load("object_model = cv\n[ObjectModel]\ncv_dt = 0.5\ncv_gate = 1\n"),
	             std::invalid_argument);
	EXPECT_THROW(load("object_model = paper_smoothing\nsmoothing = false\nSigma_s = [1 1 1]\n"),
	             std::invalid_argument);
}
