/** The -1 resolver carries its tracks lazily (CUnknownIdResolver::predict records the odometry
 * increment; a track is carried when it is read): the predictions and velocities must be
 * bit-identical to an eager carry of every track at every step (the pre-2026-11-24 code,
 * written out here), also past the resolver's flush of its increments (256) and for tracks
 * unseen for many steps. And predictStatic with the increment's rotations computed once
 * (TStaticMotion) equals predictStatic(q, u, U) bit for bit, and the formula to rounding. */
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/unknown_id_association.h>
#include <gtest/gtest.h>

#include <map>
#include <random>

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
/** The eager reference: every track carried through every increment. */
struct TEagerTrack
{
	TPoint2 last;
	Eigen::Vector2d vel = Eigen::Vector2d::Zero();
	int last_step = -1;
	bool has_vel = false;
};

void eagerPredict(std::map<int32_t, TEagerTrack>& tracks, const Eigen::Vector3d& u,
                  const Eigen::Matrix3d& U)
{
	const Eigen::Matrix2d Rt = models::rot2(u[2]).transpose();
	for (auto& [id, m] : tracks)
	{
		TPoint2 moved = m.last;
		if (m.has_vel) moved.p += m.vel;
		m.last = predictStatic(moved, u, U);
		m.vel = Rt * m.vel;
	}
}

void eagerObserve(std::map<int32_t, TEagerTrack>& tracks, int32_t id, const TPoint2& z, int step)
{
	auto it = tracks.find(id);
	if (it == tracks.end())
	{
		tracks[id] = TEagerTrack{z, Eigen::Vector2d::Zero(), step, false};
		return;
	}
	TEagerTrack& m = it->second;
	const int g = std::max(1, step - m.last_step);
	const Eigen::Vector2d prev =
	    m.has_vel ? Eigen::Vector2d(m.last.p - double(g) * m.vel) : m.last.p;
	m.vel = (z.p - prev) / double(g);
	m.has_vel = true;
	m.last = z;
	m.last_step = step;
}
}  // namespace

TEST(UnknownIdsCarry, LazyCarryIsBitIdenticalToTheEagerOne)
{
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> uni(-1, 1);
	CUnknownIdResolver lazy;
	std::map<int32_t, TEagerTrack> eager;
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 2e-4, 1e-6).asDiagonal();
	int compared = 0;
	for (int step = 0; step < 700; ++step)  // past two flushes of 256 increments
	{
		const Eigen::Vector3d u(1 + 0.1 * uni(rng), 0.05 * uni(rng), 0.02 * uni(rng));
		lazy.predict(u, U);
		eagerPredict(eager, u, U);
		for (int32_t id = 0; id < 12; ++id)
		{
			// Track id is seen every (id + 1)-th step, track 11 only twice (then carried on).
			const bool seen = id == 11 ? (step == 3 || step == 5) : step % (id + 1) == 0;
			if (!seen) continue;
			TPoint2 z;
			z.p = Eigen::Vector2d(10 * uni(rng), 10 * uni(rng));
			z.C = Eigen::Matrix2d::Identity() * 1e-3;
			if (id % 3 == 0)  // velocityWith reads (and so carries) the track first
			{
				Eigen::Vector2d v;
				ASSERT_TRUE(lazy.velocityWith(id, z, step, v) == (eager.count(id) > 0));
			}
			lazy.observe(id, z, step);
			eagerObserve(eager, id, z, step);
		}
		if (step % 97 != 0 && step != 699) continue;
		const std::vector<TTrackPrediction> p = lazy.predictions(step, 0.5);
		ASSERT_EQ(p.size(), eager.size());
		for (const TTrackPrediction& t : p)
		{
			const TEagerTrack& e = eager.at(t.target.id);
			EXPECT_EQ(t.has_vel, e.has_vel);
			// Bit-identical: the same operations in the same order.
			EXPECT_EQ(t.target.pred.p, e.last.p) << "track " << t.target.id << " step " << step;
			EXPECT_EQ(t.vel, e.vel) << "track " << t.target.id << " step " << step;
			const Eigen::Matrix2d C =
			    e.last.C + Eigen::Matrix2d::Identity() * 0.25 * std::max(1, step - e.last_step);
			EXPECT_EQ(t.target.pred.C, C) << "track " << t.target.id << " step " << step;
			++compared;
		}
	}
	EXPECT_GT(compared, 60);
}

TEST(UnknownIdsCarry, StaticMotionEqualsPredictStatic)
{
	std::mt19937 rng(3);
	std::uniform_real_distribution<double> uni(-1, 1);
	for (int i = 0; i < 50; ++i)
	{
		const Eigen::Vector3d u(uni(rng), uni(rng), 3 * uni(rng));
		Eigen::Matrix3d A = Eigen::Matrix3d::Random();
		const Eigen::Matrix3d U = A * A.transpose() * 1e-3;
		TPoint2 q;
		q.p = Eigen::Vector2d(20 * uni(rng), 20 * uni(rng));
		q.C = Eigen::Matrix2d::Identity() * 0.01 + Eigen::Matrix2d::Constant(0.001 * uni(rng));
		// The reference: predictStatic's formula (classify_evidence.h) written out here.
		const Eigen::Matrix2d Rt = models::rot2(u[2]).transpose();
		const Eigen::Vector2d d = q.p - u.head<2>();
		Eigen::Matrix<double, 2, 3> J_u;
		J_u.leftCols<2>() = -Rt;
		J_u.col(2) = models::rot2Derivative(u[2]).transpose() * d;
		const Eigen::Vector2d p = Rt * d;
		const Eigen::Matrix2d C = Rt * q.C * Rt.transpose() + J_u * U * J_u.transpose();
		const TPoint2 a = predictStatic(q, TStaticMotion(u, U));
		const TPoint2 b = predictStatic(q, u, U);
		EXPECT_EQ(a.p, b.p);  // the library's two forms: bit-identical
		EXPECT_EQ(a.C, b.C);
		// The formula written out here (another translation unit: the compiler may order the
		// products differently, so to rounding).
		EXPECT_LT((a.p - p).norm(), 1e-12 * (1 + p.norm()));
		EXPECT_LT((a.C - C).norm(), 1e-12 * (1 + C.norm()));
	}
}
