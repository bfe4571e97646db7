/** feature_labels = boxes (issue 31, box_router.h): detector boxes without IDs become corner
 * readings with persistent IDs once their track is confirmed; before that they never reach the
 * classifier (false positives never become landmarks); a box seen back to front keeps its
 * corners' IDs; malformed steps are clear errors. Synthetic boxes seen from a robot driving
 * along x (Cartesian model, the robot frame). */
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/box_router.h>
#include <gtest/gtest.h>

#include <map>

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
const auto kNone = [](int32_t) { return false; };

/** The corners FL, FR, RR, RL of a box (x, y, yaw, length, width) in its parent frame. */
std::vector<Eigen::Vector2d> corners(const Eigen::Vector3d& b, double l, double w)
{
	const Eigen::Vector2d local[] = {
	    {l / 2, w / 2}, {l / 2, -w / 2}, {-l / 2, -w / 2}, {-l / 2, w / 2}};
	std::vector<Eigen::Vector2d> out;
	for (const auto& c : local) out.push_back(b.head<2>() + models::rot2(b.z()) * c);
	return out;
}

/** A robot at (k, 0, 0) at step k (u = (1, 0, 0)); world boxes seen in its frame. */
struct TBoxWorld
{
	CBoxRouter router;
	int step = 0;
	std::vector<TBoxDetection> boxes;
	explicit TBoxWorld(const TBoxTrackerParams& p = TBoxTrackerParams())
	    : router(p, TClassifyParams())
	{
	}
	/** One step: every world box (x, y, yaw) of 4 x 2 m, yaw turned by pi where flip says. */
	TRoutedStep see(const std::vector<Eigen::Vector3d>& world, const std::vector<bool>& flip = {},
	                bool stamp = true)
	{
		const Eigen::Vector3d ego(double(step), 0, 0);
		std::vector<TReading> readings;
		boxes.clear();
		for (size_t b = 0; b < world.size(); ++b)
		{
			Eigen::Vector3d w = world[b];
			if (b < flip.size() && flip[b]) w.z() = models::wrapToPi(w.z() + M_PI);
			TBoxDetection d;
			d.group = int32_t(10 + b);
			d.cls = "Car";
			d.score = 5;
			d.pose = models::poseDifference(w, ego);
			d.extent = Eigen::Vector2d(4, 2);
			boxes.push_back(d);
			for (const auto& c : corners(d.pose, 4, 2)) readings.push_back({-1, c, d.group});
		}
		TRouterContext ctx;
		ctx.R = Eigen::Matrix2d::Identity() * 0.01;
		ctx.U = Eigen::Matrix3d::Identity() * 1e-6;
		ctx.u = step == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(1, 0, 0);
		ctx.ego = step == 0 ? ego : Eigen::Vector3d(double(step - 1), 0, 0);
		ctx.boxes = &boxes;
		if (stamp) ctx.stamp = 0.1 * step;
		router.setContext(ctx);
		router.validate(readings, "test");
		TRoutedStep r = router.route(step, readings, kNone);
		++step;
		return r;
	}
};

/** ID -> reading of a routed step. */
std::map<int32_t, Eigen::Vector2d> byId(const TRoutedStep& r)
{
	std::map<int32_t, Eigen::Vector2d> m;
	for (const auto& x : r.readings) m[x.reading.id] = x.reading.z;
	return m;
}
}  // namespace

TEST(BoxRouter, CornersReachTheClassifierOnlyOnceTheTrackIsConfirmed)
{
	TBoxTrackerParams p;
	p.min_hits = 3;
	p.birth_window = 3;
	TBoxWorld w(p);
	const Eigen::Vector3d parked(12, 4, 0.3);
	for (int k = 0; k < 2; ++k)  // hits 1 and 2: tentative
	{
		const TRoutedStep r = w.see({parked});
		EXPECT_EQ(r.skipped_box_corners, 4u) << "step " << k;
		EXPECT_TRUE(r.readings.empty()) << "step " << k;
	}
	const TRoutedStep r = w.see({parked});  // the third hit confirms it
	EXPECT_EQ(r.skipped_box_corners, 0u);
	ASSERT_EQ(r.readings.size(), 4u);
	for (int c = 0; c < 4; ++c)
	{
		EXPECT_EQ(r.readings[size_t(c)].reading.id, CBoxRouter::cornerId(0, c));
		EXPECT_EQ(r.readings[size_t(c)].reading.hint, 0);
	}
	ASSERT_NE(w.router.boxTracker(), nullptr);
	EXPECT_EQ(w.router.boxTracker()->tracks().front().state, ETrackState::Confirmed);
}

TEST(BoxRouter, AFlippedBoxKeepsItsCornersIds)
{
	TBoxWorld w;
	const Eigen::Vector3d parked(15, -3, 0.2);
	TRoutedStep r;
	for (int k = 0; k < 4; ++k) r = w.see({parked});
	const auto before = byId(r);
	ASSERT_EQ(before.size(), 4u);
	r = w.see({parked}, {true});  // the detector's heading points to the back
	const auto after = byId(r);
	ASSERT_EQ(after.size(), 4u);
	// The robot moved 1 m along x: every corner ID is the same physical corner, 1 m closer.
	for (const auto& [id, z] : before)
	{
		ASSERT_TRUE(after.count(id)) << id;
		EXPECT_NEAR((after.at(id) - (z - Eigen::Vector2d(1, 0))).norm(), 0, 1e-9) << id;
	}
}

TEST(BoxRouter, TwoBoxesGetTwoTracksAndOtherReadingsPassUnchanged)
{
	TBoxWorld w;
	TRoutedStep r;
	for (int k = 0; k < 3; ++k) r = w.see({{12, 4, 0}, {20, -4, 0}});
	std::set<int32_t> hints;
	for (const auto& x : r.readings) hints.insert(x.reading.hint);
	EXPECT_EQ(hints, (std::set<int32_t>{0, 1}));
	EXPECT_EQ(r.readings.size(), 8u);
}

TEST(BoxRouter, MalformedStepsAreClearErrors)
{
	TBoxWorld w;
	EXPECT_THROW(w.see({{12, 4, 0}}, {}, false), std::runtime_error);  // no time stamp
	// A corner whose group is no box of the step.
	TBoxWorld v;
	std::vector<TReading> rd{{-1, Eigen::Vector2d(1, 1), 99}};
	TRouterContext ctx;
	ctx.stamp = 0;
	std::vector<TBoxDetection> none;
	ctx.boxes = &none;
	v.router.setContext(ctx);
	EXPECT_THROW(v.router.route(0, rd, kNone), std::runtime_error);
	// A box with three corners.
	TBoxDetection d;
	d.group = 3;
	d.cls = "Car";
	d.pose = Eigen::Vector3d(10, 0, 0);
	d.extent = Eigen::Vector2d(4, 2);
	std::vector<TBoxDetection> one{d};
	ctx.boxes = &one;
	v.router.setContext(ctx);
	std::vector<TReading> three(3, TReading{-1, Eigen::Vector2d(10, 0), 3});
	EXPECT_THROW(v.router.route(0, three, kNone), std::runtime_error);
	// IDs of the corner range on a reading that is not a box corner.
	EXPECT_THROW(
	    v.router.validate({{CBoxRouter::kFirstCornerId, Eigen::Vector2d(1, 1), -1}}, "test"),
	    std::runtime_error);
	EXPECT_NO_THROW(v.router.validate({{7, Eigen::Vector2d(1, 1), -1}}, "test"));
	EXPECT_THROW(CBoxRouter::cornerId(0, 4), std::out_of_range);
	EXPECT_THROW(CBoxRouter::cornerId(-1, 0), std::out_of_range);
}
