/** Detection-group hints and links after a track break (doc/results/classification.md, "Hints and
 * links after a track break"): the DETECTION_GROUPS comment (dynslam/common/detection_groups.h),
 * hints as grouping evidence, contradicting hints counted, a car that reappears under new IDs
 * linked to its lost object (classify_link), and the anonymous highway end to end. Synthetic
 * tracks: router_synth.h. */
#include <dynslam/common/detection_groups.h>
#include <dynslam/common/odometry_action.h>
#include <dynslam/common/step_input.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <tuple>

#include "router_synth.h"

using namespace dynslam;
using namespace dynslam::estimator;
using router_test::TSynth;

namespace
{
/** (track ID, world point, hint) seen at a step. */
using TSeen = std::vector<std::tuple<int32_t, Eigen::Vector2d, int32_t>>;

struct THintRun : router_test::TRouterRun
{
	explicit THintRun(const TClassifyParams& p) : TRouterRun(p, 23) {}
	void run(int steps, const std::function<TSeen(int)>& world)
	{
		runReadings(steps,
		            [&](int k)
		            {
			            std::vector<TReading> rd;
			            for (const auto& [id, p, hint] : world(k))
			            {
				            TReading m{id, s.see(p)};
				            m.hint = hint;
				            rd.push_back(m);
			            }
			            return rd;
		            });
	}
};

/** A car: feature f at step k, moving v per step from base + offset. */
Eigen::Vector2d car(const Eigen::Vector2d& origin, const Eigen::Vector2d& v, int k, int f)
{
	const Eigen::Vector2d base[] = {{0, 0}, {2.5, 0}, {1, 1.5}};
	return origin + base[f] + v * (k + 1);
}
}  // namespace

TEST(ClassifyHints, DifferentBoxesMovingTogetherAreTwoObjects)
{
	// Two cars side by side, 3 m apart, same velocity: the rigid test alone groups them.
	const Eigen::Vector2d v(0.8, 0);
	const auto world = [&](int k)
	{
		TSeen w;
		for (int f = 0; f < 2; ++f) w.emplace_back(f, car({10, 3}, v, k, f), 7);
		for (int f = 0; f < 2; ++f) w.emplace_back(2 + f, car({10, 0}, v, k, f), 8);
		return w;
	};
	for (const bool hints : {false, true})
	{
		TClassifyParams p;
		p.use_hints = hints;
		THintRun run(p);
		run.run(10, world);
		const auto& t = run.r.tracks();
		for (int32_t id = 0; id < 4; ++id) ASSERT_EQ(t.at(id).cls, TrackClass::Moving) << id;
		EXPECT_EQ(t.at(0).object, t.at(1).object);
		EXPECT_EQ(t.at(2).object, t.at(3).object);
		if (hints)
			EXPECT_NE(t.at(0).object, t.at(2).object) << "boxes 7 and 8: two objects";
		else
			EXPECT_EQ(t.at(0).object, t.at(2).object) << "without hints: one rigid group";
		EXPECT_EQ(run.total(&TRoutedStep::hint_track_conflicts), 0u);
		EXPECT_EQ(run.total(&TRoutedStep::hint_group_conflicts), 0u);
	}
}

TEST(ClassifyHints, ContradictingHintsAreCountedAndTheMotionGroupingKept)
{
	// One car, tracks 0..2 in box 5; from step 8 track 1's readings say box 9 (a detector that
	// swapped boxes): counted per reading and per object-step, track 1 stays in the car's object.
	const Eigen::Vector2d v(0.8, 0);
	const auto world = [&](int k)
	{
		TSeen w;
		for (int f = 0; f < 3; ++f)
			w.emplace_back(f, car({10, 3}, v, k, f), f == 1 && k >= 8 ? 9 : 5);
		return w;
	};
	TClassifyParams p;
	p.use_hints = true;
	THintRun run(p);
	run.run(14, world);
	const auto& t = run.r.tracks();
	EXPECT_EQ(t.at(1).object, t.at(0).object);
	EXPECT_EQ(t.at(2).object, t.at(0).object);
	EXPECT_EQ(t.at(1).hint, 5) << "a track keeps its first hint";
	EXPECT_EQ(run.total(&TRoutedStep::hint_track_conflicts), 6u) << "steps 8..13";
	EXPECT_EQ(run.total(&TRoutedStep::hint_group_conflicts), 6u);
	for (int k = 8; k < 14; ++k)
	{
		EXPECT_EQ(run.at(k, 1).route, Route::ObjectTimeT) << "not dropped, step " << k;
		EXPECT_EQ(run.out[size_t(k)].hint_track_conflicts, 1u);
	}
	// Without use_hints nothing is read or counted.
	p.use_hints = false;
	THintRun off(p);
	off.run(14, world);
	EXPECT_EQ(off.total(&TRoutedStep::hint_track_conflicts), 0u);
	EXPECT_EQ(off.total(&TRoutedStep::hint_group_conflicts), 0u);
}

namespace
{
/** Car A (box 5) as tracks 0, 1 in steps 0..9 and, after 10 unseen steps, as tracks 10, 11 from
 * step 20 (vA2: its velocity then); car B (box 6) as tracks 2, 3 throughout. */
std::function<TSeen(int)> breakWorld(const Eigen::Vector2d& vA2, int32_t hintA2 = 5)
{
	return [=](int k)
	{
		const Eigen::Vector2d vA(0.8, 0), vB(0.8, 0);
		TSeen w;
		if (k < 10)
			for (int f = 0; f < 2; ++f) w.emplace_back(f, car({10, 3}, vA, k, f), 5);
		if (k >= 20)
			for (int f = 0; f < 2; ++f)
			{
				const Eigen::Vector2d at20 = car({10, 3}, vA, 19, f);
				w.emplace_back(10 + f, at20 + vA2 * (k - 19), hintA2);
			}
		for (int f = 0; f < 2; ++f) w.emplace_back(2 + f, car({10, -12}, vB, k, f), 6);
		return w;
	};
}

/** The identity of the object of track `id` at the last step (-1: none). */
int32_t identityOf(const THintRun& run, int32_t id)
{
	for (const auto& m : run.out.back().readings)
		if (m.reading.id == id) return m.identity;
	return -1;
}
}  // namespace

TEST(ClassifyHints, CarReappearingUnderNewIdsContinuesItsObject)
{
	const Eigen::Vector2d same(0.8, 0);
	struct TCase
	{
		const char* what;
		bool hints;
		TClassifyParams::Link link;
		Eigen::Vector2d vA2;
		int32_t hintA2;
		bool linked;
	};
	const TCase cases[] = {
	    {"hints: the same box", true, TClassifyParams::Link::Hints, same, 5, true},
	    {"default (hints off): no link", false, TClassifyParams::Link::Hints, same, 5, false},
	    {"all, without hints: the nearest in the gate", false, TClassifyParams::Link::All, same, 5,
	     true},
	    {"the same box, motion contradicts (reversed)", true, TClassifyParams::Link::Hints,
	     Eigen::Vector2d(-3, 0), 5, false},
	    {"another box", true, TClassifyParams::Link::All, same, 7, false},
	    {"off", true, TClassifyParams::Link::Off, same, 5, false},
	};
	for (const TCase& c : cases)
	{
		SCOPED_TRACE(c.what);
		TClassifyParams p;
		p.use_hints = c.hints;
		p.link = c.link;
		THintRun run(p);
		run.run(30, breakWorld(c.vA2, c.hintA2));
		const auto& t = run.r.tracks();
		ASSERT_EQ(t.at(10).cls, TrackClass::Moving);
		const int32_t oldA = t.at(0).object, newA = t.at(10).object, b = t.at(2).object;
		EXPECT_NE(newA, oldA) << "a new object in the estimator in every case";
		EXPECT_EQ(t.at(11).object, newA);
		EXPECT_EQ(identityOf(run, 2), b) << "car B, never lost, keeps its own identity";
		EXPECT_EQ(identityOf(run, 10), c.linked ? oldA : newA);
		EXPECT_EQ(identityOf(run, 11), identityOf(run, 10));
		EXPECT_EQ(run.total(&TRoutedStep::linked), c.linked ? 1u : 0u);
	}
}

TEST(ClassifyHints, BadKeysAreClearErrors)
{
	TClassifyParams p;
	p.link_gap = 0;
	try
	{
		CClassifyingRouter r(p);
		ADD_FAILURE() << "link_gap = 0 accepted";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("classify_link_gap"), std::string::npos);
	}
	const auto load = [](const std::string& keys)
	{
		mrpt::config::CConfigFileMemory cfg(
		    dynslam_test::highwayFilterIni("feature_labels = classify\n" + keys));
		CDynamicKFSLAM2D ekf;
		ekf.loadOptions(cfg, "DynamicKFSLAM");
		std::ostringstream dump;
		ekf.options.dumpToTextStream(dump);
		return dump.str();
	};
	EXPECT_THROW(load("[Classify]\nclassify_link = sometimes\n"), std::exception);
	EXPECT_THROW(load("[Classify]\nclassify_use_hints = maybe\n"), std::exception);
	const std::string d = load("");
	EXPECT_NE(d.find("classify_use_hints             = false"), std::string::npos) << d;
	EXPECT_NE(d.find("classify_link                  = hints"), std::string::npos);
	EXPECT_NE(d.find("classify_link_gap              = 80"), std::string::npos);
}

namespace
{
/** A step with three readings (IDs 4, -1, 9) and, if not empty, a comment with `text`. */
estimator::TStepInput parseWith(const std::string& text, bool groups = false)
{
	auto act = mrpt::obs::CActionCollection::Create();
	act->insert(makeOdometryMovement(Eigen::Vector3d(1, 0, 0), Eigen::Matrix3d::Identity() * 1e-4,
	                                 mrpt::Clock::fromDouble(0)));
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	for (const int32_t id : {4, -1, 9})
	{
		mrpt::obs::CObservationBearingRange::TMeasurement m;
		m.range = 5;
		m.yaw = 0.1f * float(id);
		m.pitch = 0;
		m.landmarkID = id;
		obs->sensedData.push_back(m);
	}
	auto sf = mrpt::obs::CSensoryFrame::Create();
	sf->insert(obs);
	if (groups) sf->insert(makeDetectionGroups({4, -1, 9}, {2, 11, -1}));
	if (!text.empty())
	{
		auto c = mrpt::obs::CObservationComment::Create();
		c->text = text;
		sf->insert(c);
	}
	return parseStepInput(act, sf, TParseOptions(), "test");
}

void expectParseError(const std::string& text, const std::string& part)
{
	try
	{
		parseWith(text);
		ADD_FAILURE() << "accepted: " << text;
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
		EXPECT_NE(std::string(e.what()).find("DETECTION_GROUPS comment, line"), std::string::npos)
		    << e.what();
	}
}
}  // namespace

TEST(DetectionGroups, CommentGivesEachReadingItsHint)
{
	const auto none = parseWith("");
	for (const auto& r : none.readings) EXPECT_EQ(r.hint, -1);
	const auto in = parseWith("", true);
	ASSERT_EQ(in.readings.size(), 3u);
	EXPECT_EQ(in.readings[0].hint, 2);
	EXPECT_EQ(in.readings[1].hint, 11) << "an ID -1 reading carries a hint too (by index)";
	EXPECT_EQ(in.readings[2].hint, -1) << "not listed: no hint";
	EXPECT_EQ(parseWith("a scenario comment\n0 4 3\n").readings[0].hint, -1)
	    << "another comment is ignored";
	EXPECT_EQ(parseWith("DETECTION_GROUPS\r\n# c\n\n2 9 0\n").readings[2].hint, 0);
	expectParseError("DETECTION_GROUPS\n0 5 2\n", "has ID 4");
	expectParseError("DETECTION_GROUPS\n3 4 2\n", "index out of range");
	expectParseError("DETECTION_GROUPS\n0 4\n", "expected");
	expectParseError("DETECTION_GROUPS\n0 4 1 7\n", "expected");
	expectParseError("DETECTION_GROUPS\n0 4 1\n0 4 2\n", "listed twice");
	expectParseError("DETECTION_GROUPS\n0 4 -3\n", "a group is an ID >= 0");
	EXPECT_THROW(makeDetectionGroups({1, 2}, {1}), std::invalid_argument);
}

namespace
{
struct THighwayRun
{
	double ate = 0, ari = 0;
	size_t linked = 0, hinted = 0, hintsWrong = 0;
};

/** config/highway_anonymous.ini with [Effects] detection_groups = true through the EKF
 * (feature_labels = classify + keys); the ARI of the object identities. */
THighwayRun highwayWithHints(const std::string& keys)
{
	std::ifstream f(std::string(DYNSLAM_CONFIG_DIR) + "/highway_anonymous.ini");
	std::stringstream ss;
	ss << f.rdbuf();
	std::string s = ss.str();
	s.replace(s.find("[Effects]"), 9, "[Effects]\ndetection_groups = true");
	const sim::TScenarioOptions o = sim::loadScenarioFromText(s);
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun sim = sim::simulateMeasurements(gt, o, o.noise_seed);
	mrpt::config::CConfigFileMemory cfg(
	    dynslam_test::highwayFilterIni("feature_labels = classify\n" + keys));
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	THighwayRun r;
	std::vector<int64_t> group;
	double se = 0;
	size_t row = 0;
	for (size_t k = 0; k < sim.actions.size(); ++k)
	{
		ekf.processActionObservation(sim.actions[k], sim.frames[k]);
		for (const auto& m : ekf.lastRoutedStep().readings)
		{
			// The simulator's hint is the true object of every object reading.
			const io::TReadingClass& c = sim.classes.at(row++);
			r.hinted += m.reading.hint >= 0;
			r.hintsWrong += m.reading.hint != c.object;
			const bool moving = !m.candidate && m.route != Route::StaticKnown &&
			                    m.route != Route::StaticNew && m.object >= 0;
			group.push_back(moving ? m.identity : -1);
		}
		r.linked += ekf.lastRoutedStep().linked;
		const auto e = ekf.getEgoPose().mean;
		se += std::pow(e.x() - gt.ego[k][0], 2) + std::pow(e.y() - gt.ego[k][1], 2);
	}
	r.ate = std::sqrt(se / double(sim.actions.size()));
	EXPECT_EQ(row, sim.classes.size());
	r.ari = eval::groupingAri(sim.classes, group);
	return r;
}
}  // namespace

TEST(ClassifyHints, AnonymousHighwayCarsLinkedAcrossTrackBreaks)
{
	const THighwayRun off = highwayWithHints("");
	const THighwayRun hints = highwayWithHints("[Classify]\nclassify_use_hints = true\n");
	const THighwayRun all = highwayWithHints("[Classify]\nclassify_link = all\n");
	std::cout << "ARI without hints " << off.ari << ", with hints " << hints.ari
	          << ", classify_link = all " << all.ari << "; linked " << hints.linked << " / "
	          << all.linked << "; ATE " << off.ate << " / " << hints.ate << " / " << all.ate
	          << " m; hinted readings " << hints.hinted << "\n";
	EXPECT_GT(hints.hinted, 0u);
	EXPECT_EQ(hints.hintsWrong, 0u) << "hints are read back as written";
	// Measured (2026-11-24): ARI 0.723 without, 0.950 with hints and with `all` (2 links each:
	// the two cars whose features all got new IDs); the ATE is the same (identities only).
	EXPECT_LT(off.ari, 0.8);
	EXPECT_EQ(off.linked, 0u);
	EXPECT_GE(hints.ari, 0.9);
	EXPECT_GE(all.ari, 0.9);
	EXPECT_EQ(hints.linked, 2u);
	EXPECT_NEAR(hints.ate, off.ate, 1e-12);
	EXPECT_NEAR(all.ate, off.ate, 1e-12);
}
