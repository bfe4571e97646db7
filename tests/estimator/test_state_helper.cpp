/** The state helper's operations (estimator/state_helper.h) against dense computations of the
 * same Gaussian transformation on random states. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/estimator/state_helper.h>
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
struct TRandomState
{
	CPaddedLayout layout;
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
};

/** Ego + 3 landmarks + a 3-dof object pose (a pad) + 1 landmark, random mean and SPD P (pads:
 * 0 mean, unit variance, uncorrelated). */
TRandomState randomState(unsigned seed)
{
	TRandomState s;
	for (int i = 0; i < 3; ++i) s.layout.append({BlockKind::StaticLandmark, 10 + i});
	TBlock pose;
	pose.kind = BlockKind::ObjectPose;
	pose.object = 0;
	pose.dim = 3;
	s.layout.append(pose);
	s.layout.append({BlockKind::StaticLandmark, 20});
	const int n = s.layout.storageDim();
	std::mt19937 rng(seed);
	std::normal_distribution<double> g;
	Eigen::MatrixXd A(n, n);
	for (int i = 0; i < n * n; ++i) A.data()[i] = g(rng);
	s.P = A * A.transpose() + Eigen::MatrixXd::Identity(n, n);
	s.x.resize(n);
	for (int i = 0; i < n; ++i) s.x[i] = 3 * g(rng);
	for (const int p : s.layout.padIndices())
	{
		s.P.row(p).setZero();
		s.P.col(p).setZero();
		s.P(p, p) = 1;
		s.x[p] = 0;
	}
	return s;
}

Eigen::MatrixXd randomMatrix(int r, int c, unsigned seed)
{
	std::mt19937 rng(seed);
	std::normal_distribution<double> g;
	Eigen::MatrixXd M(r, c);
	for (int i = 0; i < r * c; ++i) M.data()[i] = g(rng);
	return M;
}

double maxAbs(const Eigen::MatrixXd& a) { return a.cwiseAbs().maxCoeff(); }
}  // namespace

TEST(StateHelper, PropagateIsTPTtPlusQOnTheEntries)
{
	TRandomState s = randomState(1);
	const int n = int(s.x.size());
	const std::vector<int> idx{0, 1, 2, 9, 10, 11};  // the ego and the object pose
	const Eigen::MatrixXd F = randomMatrix(6, 6, 2), A = randomMatrix(6, 6, 3);
	const Eigen::MatrixXd Q = A * A.transpose();
	const Eigen::VectorXd f = randomMatrix(6, 1, 4);
	Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n), Qf = Eigen::MatrixXd::Zero(n, n);
	T(idx, idx) = F;
	Qf(idx, idx) = Q;
	const Eigen::MatrixXd Pd = T * s.P * T.transpose() + Qf;
	Eigen::VectorXd xd = s.x;
	xd(idx) = f;
	state::propagate(s.x, s.P, idx, f, F, Q);
	EXPECT_LE(maxAbs(s.P - Pd), 1e-12 * maxAbs(Pd));
	EXPECT_EQ(s.x, xd);
	EXPECT_THROW(state::propagate(s.x, s.P, idx, f.head(5), F, Q), std::invalid_argument);
}

TEST(StateHelper, UpdateIsTheDenseKalmanUpdate)
{
	TRandomState s = randomState(5);
	const int n = int(s.x.size());
	TUpdateContext ctx;  // cartesian, no gate
	ctx.R = Eigen::Matrix2d::Identity() * 0.3;
	std::vector<TStaticObservation> obs;
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(4, n);
	Eigen::VectorXd nu(4);
	const Eigen::Vector3d ego = s.x.head<3>();
	for (int j = 0; j < 2; ++j)
	{
		const int at = s.layout.first(size_t(j == 0 ? 0 : 2));
		models::Matrix23d Jx;
		Eigen::Matrix2d Jf;
		const Eigen::Vector2d f(s.x[at], s.x[at + 1]);
		const Eigen::Vector2d zhat =
		    models::observeFromSensor(ctx.model, ego, ctx.sensor_pose, f, &Jx, &Jf);
		const Eigen::Vector2d z = zhat + Eigen::Vector2d(0.4 - j, 0.2 * j);
		obs.push_back({int32_t(j), z, at});
		H.block<2, 3>(2 * j, 0) = Jx;
		H.block<2, 2>(2 * j, at) = Jf;
		nu.segment<2>(2 * j) = models::innovation(ctx.model, z, zhat);
	}
	const Eigen::MatrixXd S = H * s.P * H.transpose() + Eigen::MatrixXd::Identity(4, 4) * 0.3;
	const Eigen::MatrixXd K = s.P * H.transpose() * S.inverse();
	const Eigen::VectorXd xd = s.x + K * nu;
	const Eigen::MatrixXd Pd = s.P - K * S * K.transpose();
	CSparseUpdateEngine engine;
	const TUpdateResult r = state::update(engine, s.x, s.P, obs, ctx);
	EXPECT_EQ(r.updates, 2u);
	EXPECT_LE(maxAbs(s.x - xd), 1e-10 * maxAbs(xd));
	EXPECT_LE(maxAbs(s.P - Pd), 1e-10 * maxAbs(Pd));
}

TEST(StateHelper, AugmentIsTheStackedTransformation)
{
	for (const int d : {2, 3})  // a landmark, a 3-dof pose (with its pad)
	{
		TRandomState s = randomState(7);
		const int n = int(s.x.size());
		const std::vector<int> in{0, 1, 2, 5, 6};
		const Eigen::MatrixXd J = randomMatrix(d, 5, 8), A = randomMatrix(d, d, 9);
		const Eigen::MatrixXd R = A * A.transpose();
		const Eigen::VectorXd g = randomMatrix(d, 1, 10);
		Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n + d, n);
		T.topRows(n).setIdentity();
		T(Eigen::seqN(n, d), in) = J;
		Eigen::MatrixXd Pd = T * s.P * T.transpose();
		Pd.bottomRightCorner(d, d) += R;
		TBlock b;
		b.kind = d == 2 ? BlockKind::StaticLandmark : BlockKind::ObjectPose;
		b.id = d == 2 ? 30 : -1;
		b.object = d == 2 ? -1 : 1;
		b.dim = d;
		const size_t blocks = s.layout.size();
		state::augment(s.x, s.P, s.layout, b, g, in, J, R);
		ASSERT_EQ(s.layout.size(), blocks + 1);
		ASSERT_EQ(s.x.size(), s.layout.storageDim());
		const int w = int(s.x.size()) - n;
		EXPECT_EQ(w, d == 2 ? 2 : 4);
		EXPECT_LE(maxAbs(s.P.topLeftCorner(n + d, n + d) - Pd), 1e-12 * maxAbs(Pd)) << d;
		EXPECT_EQ(s.x.segment(n, d), g);
		if (w > d)  // the pad: mean 0, variance 1, uncorrelated
		{
			EXPECT_EQ(s.x[n + d], 0.0);
			EXPECT_EQ(s.P(n + d, n + d), 1.0);
			EXPECT_EQ(s.P.row(n + d).head(n + d).cwiseAbs().maxCoeff(), 0.0);
		}
		EXPECT_THROW(state::augment(s.x, s.P, s.layout, b, g, {0, 1}, J, R), std::invalid_argument);
	}
}

TEST(StateHelper, MarginalizeKeepsTheRestExactly)
{
	TRandomState s = randomState(11);
	const TRandomState before = s;
	const std::vector<bool> remove{false, true, false, true, false};  // landmark 11, the pose
	const std::vector<int> keep{0, 1, 2, 3, 4, 7, 8, 13, 14};
	state::marginalize(s.x, s.P, s.layout, remove);
	EXPECT_EQ(s.x, before.x(keep));
	EXPECT_EQ(Eigen::MatrixXd(s.P), Eigen::MatrixXd(before.P(keep, keep)));
	ASSERT_EQ(s.layout.size(), 3u);
	EXPECT_EQ(s.layout[2].id, 20);
	EXPECT_THROW(state::marginalize(s.x, s.P, s.layout, {true}), std::invalid_argument);
}

TEST(StateHelper, ReplaceIsTPTtWithOverlappingInAndOut)
{
	TRandomState s = randomState(13);
	const int n = int(s.x.size());
	// out = landmark 12's entries, computed from the object pose and itself (they overlap).
	const std::vector<int> in{9, 10, 11, 7, 8}, out{7, 8};
	const Eigen::MatrixXd J = randomMatrix(2, 5, 14);
	const Eigen::VectorXd g = randomMatrix(2, 1, 15);
	Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n);
	T.row(7).setZero();
	T.row(8).setZero();
	T(out, in) = J;
	const Eigen::MatrixXd Pd = T * s.P * T.transpose();
	Eigen::VectorXd xd = s.x;
	xd(out) = g;
	state::replace(s.x, s.P, in, out, g, J);
	EXPECT_LE(maxAbs(s.P - Pd), 1e-12 * maxAbs(Pd));
	EXPECT_EQ(s.x, xd);
	EXPECT_EQ(Eigen::MatrixXd(s.P(out, Eigen::all)),
	          Eigen::MatrixXd(s.P(Eigen::all, out).transpose()));  // rows out mirror columns out
	EXPECT_THROW(state::replace(s.x, s.P, in, out, g, J.leftCols(4)), std::invalid_argument);
}
