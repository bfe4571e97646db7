/** CBoxTracker (estimator/box_tracker.h): the Kalman filter against a dense computation written
 * here, every decision threshold on both sides (birth window, max_age, the Mahalanobis gate, the
 * IoU threshold, min_score, the flip at pi/2), classes, a case where greedy nearest neighbour
 * and the Hungarian assignment differ, overridePrediction and bad input.
 *
 * Numbers by hand: with the default meas_std (0.3, 0.3, 0.15, 0.3, 0.15) a new track's centre
 * covariance is 0.09 I; a box compared with it before any predict() has S = 0.18 I, so the
 * squared Mahalanobis distance of a box at distance d is d^2 / 0.18 and the 0.99 gate
 * (-2 ln 0.01 = 9.21034) is reached at d = sqrt(0.18 * 9.21034) = 1.28758 m. Two 4 x 2 m boxes
 * with the same heading shifted by s along their length have IoU (4 - s) / (4 + s): 0.25 at
 * s = 2.4 m. */
#include <dynslam/estimator/box_tracker.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

using namespace dynslam::estimator;

namespace
{
TWorldBox box(double x, double y, double yaw = 0, const std::string& cls = "Car", double score = 1)
{
	TWorldBox b;
	b.pose << x, y, yaw;
	b.extent << 4, 2;
	b.cls = cls;
	b.score = score;
	return b;
}

TBoxTrackerParams params(int min_hits = 1, int window = 1, int max_age = 1)
{
	TBoxTrackerParams p;
	p.min_hits = min_hits;
	p.birth_window = window;
	p.max_age = max_age;
	return p;
}

const double kGateDistance = std::sqrt(0.18 * (-2 * std::log(0.01)));
}  // namespace

TEST(BoxTracker, KalmanStepsMatchDenseComputation)
{
	TBoxTrackerParams p = params();
	p.accel_std = 2.0;
	p.yaw_std = 0.05;
	p.extent_std = 0.02;
	p.velocity_std = 4.0;
	CBoxTracker trk(p);
	TWorldBox b0 = box(10, -3, 0.4);
	b0.centre_cov << 0.04, 0.01, 0.01, 0.02;
	trk.update({b0});
	ASSERT_EQ(trk.tracks().size(), 1u);
	// birth: x = (box, 0, 0), P = diag(meas_std^2) + centre_cov, velocity_std^2
	Eigen::MatrixXd P = Eigen::MatrixXd::Zero(7, 7);
	const double ms[5] = {0.3, 0.3, 0.15, 0.3, 0.15};
	for (int i = 0; i < 5; ++i) P(i, i) = ms[i] * ms[i];
	P(0, 0) += 0.04;
	P(1, 1) += 0.02;
	P(0, 1) = P(1, 0) = 0.01;
	P(5, 5) = P(6, 6) = 16;
	Eigen::VectorXd x(7);
	x << 10, -3, 0.4, 4, 2, 0, 0;
	EXPECT_LT((trk.tracks()[0].x - x).norm(), 1e-12);
	EXPECT_LT((trk.tracks()[0].P - P).norm(), 1e-12);
	// predict by dt = 0.25: F with dt in (x, vx), (y, vy); Q of a white acceleration per axis
	const double dt = 0.25;
	Eigen::MatrixXd F = Eigen::MatrixXd::Identity(7, 7), Q = Eigen::MatrixXd::Zero(7, 7);
	F(0, 5) = F(1, 6) = dt;
	for (int a = 0; a < 2; ++a)
	{
		Q(a, a) = 4.0 * dt * dt * dt * dt / 4;
		Q(a, a + 5) = Q(a + 5, a) = 4.0 * dt * dt * dt / 2;
		Q(a + 5, a + 5) = 4.0 * dt * dt;
	}
	Q(2, 2) = 0.05 * 0.05;
	Q(3, 3) = Q(4, 4) = 0.02 * 0.02;
	trk.predict(dt);
	x = F * x;
	P = F * P * F.transpose() + Q;
	EXPECT_LT((trk.tracks()[0].x - x).norm(), 1e-12);
	EXPECT_LT((trk.tracks()[0].P - P).norm(), 1e-12);
	// update with a box (z = x, y, yaw, l, w): K = P H' (H P H' + R)^-1, P+ = (I - K H) P
	const TWorldBox b1 = box(10.2, -2.9, 0.45);
	trk.update({b1});
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(5, 7);
	H.leftCols(5).setIdentity();
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(5, 5);
	for (int i = 0; i < 5; ++i) R(i, i) = ms[i] * ms[i];
	Eigen::VectorXd z(5);
	z << 10.2, -2.9, 0.45, 4, 2;
	const Eigen::MatrixXd K = P * H.transpose() * (H * P * H.transpose() + R).inverse();
	x = x + K * (z - H * x);
	P = (Eigen::MatrixXd::Identity(7, 7) - K * H) * P;
	EXPECT_LT((trk.tracks()[0].x - x).norm(), 1e-10);
	EXPECT_LT((trk.tracks()[0].P - P).norm(), 1e-10);
	EXPECT_GT(trk.tracks()[0].x(5), 0);  // the velocity learnt from the displacement
}

TEST(BoxTracker, BirthExactlyAtTheMthHitWithinTheWindow)
{
	// M = 3, N = 3: confirmed in the third consecutive frame with a box, not before
	{
		CBoxTracker t(params(3, 3, 5));
		EXPECT_EQ(t.update({box(0, 0)}).births, 1u);
		EXPECT_EQ(t.tracks()[0].state, ETrackState::Tentative);
		EXPECT_EQ(t.update({box(0, 0)}).confirmations, 0u);
		EXPECT_EQ(t.tracks()[0].state, ETrackState::Tentative);
		EXPECT_EQ(t.update({box(0, 0)}).confirmations, 1u);
		EXPECT_EQ(t.tracks()[0].state, ETrackState::Confirmed);
	}
	// M = 2, N = 3: hit, miss, hit: the 2nd hit in the 3rd frame confirms
	{
		CBoxTracker t(params(2, 3, 5));
		t.update({box(0, 0)});
		t.update({});
		EXPECT_EQ(t.tracks()[0].state, ETrackState::Tentative);
		EXPECT_EQ(t.update({box(0, 0)}).confirmations, 1u);
		EXPECT_EQ(t.tracks()[0].state, ETrackState::Confirmed);
	}
	// M = 2, N = 3: hit, miss, miss: cannot reach 2 hits in the window: deleted in frame 3; the
	// 4th frame's box starts a new track (ID 1)
	{
		CBoxTracker t(params(2, 3, 5));
		t.update({box(0, 0)});
		EXPECT_EQ(t.update({}).deletions, 0u);
		EXPECT_EQ(t.update({}).deletions, 1u);
		EXPECT_TRUE(t.tracks().empty());
		EXPECT_EQ(t.update({box(0, 0)}).track[0], 1);
	}
	// M = 2, N = 4: the 2nd hit one frame later (frame 4) is still inside the window
	{
		CBoxTracker t(params(2, 4, 5));
		t.update({box(0, 0)});
		t.update({});
		t.update({});
		const TBoxAssignment a = t.update({box(0, 0)});
		EXPECT_EQ(a.track[0], 0);
		EXPECT_EQ(a.confirmations, 1u);
	}
}

TEST(BoxTracker, DeletionAfterExactlyMaxAgeMisses)
{
	CBoxTracker t(params(1, 1, 3));
	t.update({box(0, 0)});
	EXPECT_EQ(t.tracks()[0].state, ETrackState::Confirmed);
	EXPECT_EQ(t.update({}).deletions, 0u);
	EXPECT_EQ(t.tracks()[0].state, ETrackState::Lost);
	EXPECT_EQ(t.update({}).deletions, 0u);  // 2 misses < max_age 3: kept
	EXPECT_EQ(t.tracks()[0].misses, 2);
	EXPECT_EQ(t.update({}).deletions, 1u);  // the 3rd: deleted
	EXPECT_TRUE(t.tracks().empty());
	// Lost -> Confirmed on a hit, the miss count reset
	CBoxTracker u(params(1, 1, 3));
	u.update({box(0, 0)});
	u.update({});
	u.update({});
	EXPECT_EQ(u.tracks()[0].state, ETrackState::Lost);
	u.update({box(0, 0)});
	EXPECT_EQ(u.tracks()[0].state, ETrackState::Confirmed);
	EXPECT_EQ(u.tracks()[0].misses, 0);
	EXPECT_EQ(u.tracks()[0].hits, 2);
	EXPECT_EQ(u.tracks()[0].age, 3);
	// a Tentative track dies of max_age too (AB3DMOT), before its window ends
	CBoxTracker v(params(3, 10, 2));
	v.update({box(0, 0)});
	EXPECT_EQ(v.update({}).deletions, 0u);
	EXPECT_EQ(v.update({}).deletions, 1u);
}

TEST(BoxTracker, MahalanobisGateOnBothSides)
{
	for (const double f : {0.999, 1.001})
	{
		CBoxTracker t(params());
		t.update({box(0, 0)});
		const TBoxAssignment a =
		    t.update({box(f * kGateDistance / std::sqrt(2.0), f * kGateDistance / std::sqrt(2.0))});
		EXPECT_EQ(a.track[0], f < 1 ? 0 : 1) << f;
		EXPECT_EQ(a.births, f < 1 ? 0u : 1u) << f;
		EXPECT_EQ(a.deletions, f < 1 ? 0u : 1u) << f;  // max_age 1: the missed track dies
	}
}

TEST(BoxTracker, IoUThresholdOnBothSides)
{
	for (const double s : {2.39, 2.41})
	{
		TBoxTrackerParams p = params();
		p.metric = "bev_iou";
		p.min_iou = 0.25;
		CBoxTracker t(p);
		t.update({box(0, 0, 0.7)});
		// shifted by s along the heading 0.7
		const TBoxAssignment a = t.update({box(s * std::cos(0.7), s * std::sin(0.7), 0.7)});
		EXPECT_EQ(a.track[0], s < 2.4 ? 0 : 1) << s;
	}
}

TEST(BoxTracker, ClassesNeverPair)
{
	for (const std::string metric : {"mahalanobis", "bev_iou"})
	{
		TBoxTrackerParams p = params(1, 1, 5);
		p.metric = metric;
		CBoxTracker t(p);
		t.update({box(0, 0)});
		const TBoxAssignment a = t.update({box(0, 0, 0, "Pedestrian")});
		EXPECT_EQ(a.track[0], 1) << metric;
		EXPECT_EQ(a.births, 1u);
		EXPECT_EQ(t.update({box(0, 0, 0, "Car")}).track[0], 0) << metric;
	}
}

TEST(BoxTracker, MinScoreOnBothSides)
{
	TBoxTrackerParams p = params();
	p.min_score = 0.5;
	CBoxTracker t(p);
	EXPECT_EQ(t.update({box(0, 0, 0, "Car", 0.4999)}).track[0], -1);
	EXPECT_TRUE(t.tracks().empty());
	EXPECT_EQ(t.update({box(0, 0, 0, "Car", 0.5)}).track[0], 0);
	// a box under min_score still updates a track it is assigned to
	EXPECT_EQ(t.update({box(0.1, 0, 0, "Car", 0.1)}).track[0], 0);
	EXPECT_EQ(t.tracks()[0].score, 0.1);
}

TEST(BoxTracker, HungarianWhereGreedyNearestNeighbourDiffers)
{
	// tracks T0 at x = 0, T1 at x = -2 (gate radius 1.2876 m); boxes b0 at -0.9, b1 at +1.0.
	// Greedy takes the nearest pair first: (T0, b0) at 0.9 m; then T1 - b1 (3.0 m) is gated:
	// one pair. The assignment with the most pairs: (T0, b1) 1.0 m and (T1, b0) 1.1 m.
	const std::vector<double> tx = {0, -2}, bx = {-0.9, 1.0};
	Eigen::Matrix2d d2;
	for (int i = 0; i < 2; ++i)
		for (int j = 0; j < 2; ++j) d2(i, j) = (tx[i] - bx[j]) * (tx[i] - bx[j]) / 0.18;
	const double gate = -2 * std::log(0.01);
	Eigen::Index gi = 0, gj = 0;
	d2.minCoeff(&gi, &gj);
	EXPECT_EQ(gi, 0);
	EXPECT_EQ(gj, 0);                               // greedy's first pair: (T0, b0)
	EXPECT_GT(d2(1, 1), gate);                      // its second would be gated
	EXPECT_LT(std::max(d2(0, 1), d2(1, 0)), gate);  // both crossed pairs allowed
	CBoxTracker t(params(1, 1, 5));
	t.update({box(0, 0), box(-2, 0)});
	const TBoxAssignment a = t.update({box(-0.9, 0), box(1.0, 0)});
	EXPECT_EQ(a.track, (std::vector<int32_t>{1, 0}));
	EXPECT_EQ(a.births, 0u);
}

TEST(BoxTracker, FlipByPiKeepsTheHeading)
{
	// the track's heading 0.2; a box at 0.25 + pi is turned back to 0.25: the same update as a
	// twin tracker given 0.25, reported flipped
	CBoxTracker a(params()), b(params());
	a.update({box(0, 0, 0.2)});
	b.update({box(0, 0, 0.2)});
	const TBoxAssignment fa = a.update({box(0.1, 0, 0.25 + M_PI)});
	const TBoxAssignment fb = b.update({box(0.1, 0, 0.25)});
	EXPECT_TRUE(fa.flipped[0]);
	EXPECT_FALSE(fb.flipped[0]);
	EXPECT_EQ(fa.track[0], 0);
	EXPECT_LT((a.tracks()[0].x - b.tracks()[0].x).norm(), 1e-12);
	EXPECT_NEAR(a.tracks()[0].x(2), 0.225, 1e-12);  // equal variances: the mean of 0.2, 0.25
	// both sides of pi/2: turned only beyond it (wrapped differences, also across -pi)
	for (const double d : {M_PI / 2 - 1e-3, M_PI / 2 + 1e-3, -M_PI / 2 - 1e-3})
	{
		TBoxTrackerParams p = params();
		p.meas_std(2) = 10;  // a heading that barely moves the track
		CBoxTracker c(p);
		c.update({box(0, 0, 3.0)});
		const TBoxAssignment f = c.update({box(0, 0, 3.0 + d)});
		EXPECT_EQ(bool(f.flipped[0]), std::abs(d) > M_PI / 2) << d;
	}
}

TEST(BoxTracker, OverridePredictionChangesTheAssociation)
{
	for (const bool over : {false, true})
	{
		CBoxTracker t(params(1, 1, 5));
		t.update({box(0, 0)});
		t.predict(0.1);
		if (over)
			t.overridePrediction(0, Eigen::Vector2d(1.9, 0), 0.01 * Eigen::Matrix2d::Identity());
		// 2 m from the track's own prediction (gated), 0.1 m from the override
		EXPECT_EQ(t.update({box(2.0, 0)}).track[0], over ? 0 : 1);
	}
	// Jeffrey's rule: the new centre and covariance, the conditional of the rest unchanged
	CBoxTracker t(params(1, 1, 5));
	t.update({box(0, 0, 0.3)});
	t.predict(0.1);
	t.update({box(0.5, 0.1, 0.3)});
	t.predict(0.1);
	const Matrix7d P0 = t.tracks()[0].P;
	Eigen::Matrix2d C;
	C << 0.05, 0.01, 0.01, 0.03;
	t.overridePrediction(0, Eigen::Vector2d(1.0, 0.2), C);
	const Matrix7d P1 = t.tracks()[0].P;
	EXPECT_LT((t.tracks()[0].x.head<2>() - Eigen::Vector2d(1.0, 0.2)).norm(), 1e-15);
	EXPECT_LT((P1.topLeftCorner<2, 2>() - C).norm(), 1e-15);
	auto conditional = [](const Matrix7d& P)
	{
		const Eigen::Matrix<double, 5, 2> G =
		    P.bottomLeftCorner<5, 2>() * P.topLeftCorner<2, 2>().inverse();
		return std::make_pair(G, Eigen::Matrix<double, 5, 5>(P.bottomRightCorner<5, 5>() -
		                                                     G * P.topRightCorner<2, 5>()));
	};
	EXPECT_LT((conditional(P0).first - conditional(P1).first).norm(), 1e-9);
	EXPECT_LT((conditional(P0).second - conditional(P1).second).norm(), 1e-9);
	EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix7d>(P1).eigenvalues().minCoeff(), 0);
	// bad input
	EXPECT_THROW(t.overridePrediction(7, Eigen::Vector2d::Zero(), C), std::invalid_argument);
	EXPECT_THROW(t.overridePrediction(0, Eigen::Vector2d(NAN, 0), C), std::invalid_argument);
	Eigen::Matrix2d bad;
	bad << 1, 2, 2, 1;  // indefinite
	EXPECT_THROW(t.overridePrediction(0, Eigen::Vector2d::Zero(), bad), std::invalid_argument);
	bad << 1, 0.1, 0, 1;  // not symmetric
	EXPECT_THROW(t.overridePrediction(0, Eigen::Vector2d::Zero(), bad), std::invalid_argument);
}

TEST(BoxTracker, BadInput)
{
	const std::vector<std::function<void(TBoxTrackerParams&)>> bad = {
	    [](TBoxTrackerParams& p) { p.metric = "iou"; },
	    [](TBoxTrackerParams& p) { p.gate_prob = 0; },
	    [](TBoxTrackerParams& p) { p.gate_prob = 1; },
	    [](TBoxTrackerParams& p) { p.min_iou = 0; },
	    [](TBoxTrackerParams& p) { p.min_iou = 1.01; },
	    [](TBoxTrackerParams& p) { p.min_hits = 0; },
	    [](TBoxTrackerParams& p) { p.birth_window = p.min_hits - 1; },
	    [](TBoxTrackerParams& p) { p.max_age = 0; },
	    [](TBoxTrackerParams& p) { p.min_score = NAN; },
	    [](TBoxTrackerParams& p) { p.accel_std = 0; },
	    [](TBoxTrackerParams& p) { p.yaw_std = -1; },
	    [](TBoxTrackerParams& p) { p.extent_std = INFINITY; },
	    [](TBoxTrackerParams& p) { p.velocity_std = NAN; },
	    [](TBoxTrackerParams& p) { p.meas_std(4) = 0; },
	    [](TBoxTrackerParams& p) { p.meas_std(2) = NAN; }};
	for (size_t i = 0; i < bad.size(); ++i)
	{
		TBoxTrackerParams p;
		EXPECT_NO_THROW(p.validate());
		bad[i](p);
		EXPECT_THROW(p.validate(), std::invalid_argument) << i;
		EXPECT_THROW(CBoxTracker{p}, std::invalid_argument) << i;
	}
	TBoxTrackerParams edge;
	edge.min_iou = 1;
	edge.birth_window = edge.min_hits;
	EXPECT_NO_THROW(edge.validate());

	CBoxTracker t(params(1, 1, 5));
	t.update({box(0, 0)});
	for (const double dt : {0.0, -0.1, double(NAN), double(INFINITY)})
		EXPECT_THROW(t.predict(dt), std::invalid_argument) << dt;
	std::vector<TWorldBox> boxes(4, box(0, 0));
	boxes[0].pose.x() = NAN;
	boxes[1].extent.y() = 0;
	boxes[2].score = NAN;
	boxes[3].centre_cov << 1, 0.5, 0, 1;
	for (const TWorldBox& b : boxes)
	{
		EXPECT_THROW(t.update({box(0, 0), b}), std::invalid_argument);
		ASSERT_EQ(t.tracks().size(), 1u);  // nothing changed
		EXPECT_EQ(t.tracks()[0].age, 0);
	}
	TWorldBox b = box(0, 0);
	b.centre_cov << -1, 0, 0, 1;
	EXPECT_THROW(t.update({b}), std::invalid_argument);
}
