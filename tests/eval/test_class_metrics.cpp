/** Classification and grouping metrics (issue 12) against hand-computed values. */
#include <dynslam/eval/class_metrics.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace dynslam;
using namespace dynslam::eval;

namespace
{
io::TReadingClass row(int step, int index, int32_t id, io::TrueClass c, int32_t object,
                      int32_t feature)
{
	io::TReadingClass r;
	r.step = step;
	r.t = step;
	r.index = index;
	r.id = id;
	r.true_id = c == io::TrueClass::Clutter ? -1 : id;
	r.cls = c;
	r.object = object;
	r.feature = feature;
	return r;
}
constexpr auto S = io::TrueClass::Static;
constexpr auto M = io::TrueClass::Moving;
constexpr auto C = io::TrueClass::Clutter;
constexpr auto dS = Decision::Static;
constexpr auto dM = Decision::Moving;
constexpr auto dU = Decision::Undecided;
}  // namespace

TEST(ClassMetrics, AdjustedRandIndexScikitLearnExamples)
{
	// The examples of sklearn.metrics.adjusted_rand_score's documentation.
	EXPECT_DOUBLE_EQ(adjustedRandIndex({0, 0, 1, 1}, {0, 0, 1, 1}), 1.0);
	EXPECT_DOUBLE_EQ(adjustedRandIndex({0, 0, 1, 1}, {1, 1, 0, 0}), 1.0);          // renamed
	EXPECT_NEAR(adjustedRandIndex({0, 0, 1, 2}, {0, 0, 1, 1}), 4.0 / 7.0, 1e-15);  // 0.57...
	EXPECT_NEAR(adjustedRandIndex({0, 0, 1, 1}, {0, 0, 1, 2}), 4.0 / 7.0, 1e-15);
	EXPECT_DOUBLE_EQ(adjustedRandIndex({0, 0, 0, 0}, {0, 1, 2, 3}), 0.0);
	EXPECT_DOUBLE_EQ(adjustedRandIndex({0, 0, 1, 1}, {0, 1, 0, 1}), -0.5);
}

TEST(ClassMetrics, AdjustedRandIndexHandComputed)
{
	// n = 6: truth {a,a,a,b,b,b}, estimate {x,x,y,y,z,z}. n_ij: (a,x)=2 (a,y)=1 (b,y)=1 (b,z)=2
	// -> sum C(n_ij,2) = 2; a_i = 3,3 -> 6; b_j = 2,2,2 -> 3; E = 6*3/15 = 1.2;
	// max = (6+3)/2 = 4.5; ARI = (2 - 1.2) / (4.5 - 1.2) = 0.8 / 3.3 = 8/33.
	EXPECT_NEAR(adjustedRandIndex({0, 0, 0, 1, 1, 1}, {7, 7, 8, 8, 9, 9}), 8.0 / 33.0, 1e-15);
	// Symmetric in its arguments.
	EXPECT_NEAR(adjustedRandIndex({7, 7, 8, 8, 9, 9}, {0, 0, 0, 1, 1, 1}), 8.0 / 33.0, 1e-15);
}

TEST(ClassMetrics, AdjustedRandIndexDegenerateCases)
{
	EXPECT_DOUBLE_EQ(adjustedRandIndex({5}, {9}), 1.0);                    // one item
	EXPECT_DOUBLE_EQ(adjustedRandIndex({1, 1, 1}, {2, 2, 2}), 1.0);        // one cluster each
	EXPECT_DOUBLE_EQ(adjustedRandIndex({1, 2, 3}, {4, 5, 6}), 1.0);        // singletons each
	EXPECT_DOUBLE_EQ(adjustedRandIndex({1, 2, 3, 4}, {0, 0, 0, 0}), 0.0);  // one vs singletons
	EXPECT_THROW(adjustedRandIndex({}, {}), std::invalid_argument);
	EXPECT_THROW(adjustedRandIndex({1, 2}, {1}), std::invalid_argument);
}

TEST(ClassMetrics, PerReadingScores)
{
	// 3 moving (2 decided moving, 1 undecided), 2 static (1 decided moving), 1 clutter (static).
	const std::vector<io::TReadingClass> t = {row(0, 0, 1, M, 0, 0),  row(0, 1, 2, M, 0, 1),
	                                          row(0, 2, 3, M, 0, 2),  row(0, 3, 4, S, -1, 4),
	                                          row(0, 4, 5, S, -1, 5), row(0, 5, 6, C, -1, -1)};
	const TBinaryScores s = perReadingScores(t, {dM, dM, dU, dM, dS, dS});
	EXPECT_EQ(s.tp, 2u);
	EXPECT_EQ(s.fp, 1u);
	EXPECT_EQ(s.fn, 1u);
	EXPECT_EQ(s.tn, 2u);
	EXPECT_EQ(s.undecided, 1u);
	EXPECT_DOUBLE_EQ(s.precision, 2.0 / 3.0);
	EXPECT_DOUBLE_EQ(s.recall, 2.0 / 3.0);
	EXPECT_DOUBLE_EQ(s.f1, 2.0 / 3.0);
	// clutter decided moving is a false positive
	EXPECT_EQ(perReadingScores(t, {dM, dM, dM, dS, dS, dM}).fp, 1u);
	// nothing moving, nothing decided moving: all NaN; decided moving only: precision 0
	const TBinaryScores n = perReadingScores({row(0, 0, 4, S, -1, 4)}, {dS});
	EXPECT_TRUE(std::isnan(n.precision) && std::isnan(n.recall) && std::isnan(n.f1));
	const TBinaryScores f = perReadingScores({row(0, 0, 4, S, -1, 4)}, {dM});
	EXPECT_DOUBLE_EQ(f.precision, 0.0);
	EXPECT_DOUBLE_EQ(f.f1, 0.0);
	EXPECT_TRUE(std::isnan(f.recall));
	EXPECT_THROW(perReadingScores(t, {dM}), std::invalid_argument);
}

TEST(ClassMetrics, PerTrackScoresUseTheLastReading)
{
	// Track 10: static at 0, moving at 1 and 2 (drives off), final decision moving -> tp.
	// Track 11: moving, final decision static -> fn. Track 12: static, last decided moving -> fp.
	// Rows given out of order; id -1 rows are not tracks.
	const std::vector<io::TReadingClass> t = {row(2, 0, 10, M, 0, 0),   row(0, 0, 10, S, 0, 0),
	                                          row(1, 0, 10, M, 0, 0),   row(0, 1, 11, M, 1, 0),
	                                          row(1, 1, 11, M, 1, 0),   row(0, 2, 12, S, -1, 12),
	                                          row(1, 2, 12, S, -1, 12), row(1, 3, -1, C, -1, -1)};
	const TBinaryScores s = perTrackScores(t, {dM, dS, dS, dM, dS, dS, dM, dM});
	EXPECT_EQ(s.tp, 1u);
	EXPECT_EQ(s.fn, 1u);
	EXPECT_EQ(s.fp, 1u);
	EXPECT_EQ(s.tn, 0u);
	EXPECT_DOUBLE_EQ(s.f1, 0.5);
}

TEST(ClassMetrics, DetectionDelayAfterOnset)
{
	// Feature (3,0): static at steps 0..2, moving from 3; decided moving at 5 -> delay 2.
	// Feature (3,1): onset at 3, missed readings at 4, decided at 6 -> delay 3 (steps, not rows).
	// Feature (4,0): onset at 3, never decided moving -> missed.
	std::vector<io::TReadingClass> t;
	std::vector<Decision> d;
	for (int k = 0; k <= 7; ++k)
	{
		t.push_back(row(k, 0, 30, k < 3 ? S : M, 3, 0));
		d.push_back(k >= 5 ? dM : dS);
		if (k != 4)
		{
			t.push_back(row(k, 1, 31, k < 3 ? S : M, 3, 1));
			d.push_back(k >= 6 ? dM : dS);
		}
		t.push_back(row(k, 2, 40, k < 3 ? S : M, 4, 0));
		d.push_back(k < 3 ? dM : dS);  // wrong before the onset: not a detection
	}
	const TDelaySummary s = detectionDelays(t, d);
	ASSERT_EQ(s.onsets.size(), 3u);
	EXPECT_EQ(s.onsets[0].delay, 2);
	EXPECT_EQ(s.onsets[0].onset_step, 3);
	EXPECT_EQ(s.onsets[1].delay, 3);
	EXPECT_EQ(s.onsets[2].delay, -1);
	EXPECT_EQ(s.detected, 2u);
	EXPECT_EQ(s.missed, 1u);
	EXPECT_DOUBLE_EQ(s.mean_delay, 2.5);
	EXPECT_EQ(s.max_delay, 3);
	// Moving from the first sighting: an onset only with includeFirstSightings.
	const std::vector<io::TReadingClass> m = {row(0, 0, 50, M, 5, 0), row(1, 0, 50, M, 5, 0)};
	EXPECT_TRUE(detectionDelays(m, {dS, dM}).onsets.empty());
	const TDelaySummary f = detectionDelays(m, {dS, dM}, true);
	ASSERT_EQ(f.onsets.size(), 1u);
	EXPECT_EQ(f.onsets[0].delay, 1);
	EXPECT_EQ(detectionDelays(m, {dM, dM}, true).onsets.at(0).delay, 0);  // at the onset itself
}

TEST(ClassMetrics, GroupingAri)
{
	// Moving readings of objects 0, 0, 1, 1 grouped as {a, a, b, b}: 1; a static reading and an
	// ungrouped one (-1 -> singleton) change it to the [0,0,1,1] vs [0,0,1,s] example: 4/7.
	const std::vector<io::TReadingClass> t = {row(0, 0, 1, M, 0, 0), row(0, 1, 2, M, 0, 1),
	                                          row(0, 2, 3, M, 1, 0), row(0, 3, 4, M, 1, 1),
	                                          row(0, 4, 5, S, -1, 5)};
	EXPECT_DOUBLE_EQ(groupingAri(t, {7, 7, 8, 8, 7}), 1.0);
	EXPECT_NEAR(groupingAri(t, {7, 7, 8, -1, 7}), 4.0 / 7.0, 1e-15);
	EXPECT_TRUE(std::isnan(groupingAri({row(0, 0, 5, S, -1, 5)}, {0})));
	EXPECT_THROW(groupingAri(t, {1}), std::invalid_argument);
}

TEST(ClassMetrics, IdentityCounts)
{
	// True objects 0 (two tracks after a break) and 1; a static reading never counts.
	const std::vector<io::TReadingClass> t = {row(0, 0, 1, M, 0, 0), row(1, 0, 2, M, 0, 0),
	                                          row(0, 1, 3, M, 1, 0), row(1, 1, 4, M, 1, 0),
	                                          row(0, 2, 5, S, -1, 5)};
	// The break linked (both tracks of object 0 in identity 7): one identity per true object.
	TIdentityCounts c = identityCounts(t, {7, 7, 8, 8, 9});
	EXPECT_EQ(c.true_objects, 2u);
	EXPECT_EQ(c.identities, 2u);
	EXPECT_EQ(c.impure, 0u);
	EXPECT_EQ(c.split, 0u);
	// Not linked: object 0 in identities 7 and 6 (split); an ungrouped reading counts nowhere.
	c = identityCounts(t, {7, 6, 8, -1, 9});
	EXPECT_EQ(c.identities, 3u);
	EXPECT_EQ(c.impure, 0u);
	EXPECT_EQ(c.split, 1u);
	// Linked wrongly: identity 7 holds readings of objects 0 and 1.
	c = identityCounts(t, {7, 7, 7, 8, 9});
	EXPECT_EQ(c.identities, 2u);
	EXPECT_EQ(c.impure, 1u);
	EXPECT_EQ(c.split, 1u);
	EXPECT_THROW(identityCounts(t, {1}), std::invalid_argument);
}

TEST(ClassMetrics, WrongStaticLandmarks)
{
	const std::vector<io::TReadingClass> t = {row(0, 0, 1, S, -1, 1), row(0, 1, 2, S, 0, 0),
	                                          row(1, 0, 2, M, 0, 0), row(0, 2, 3, C, -1, -1),
	                                          row(0, 3, 4, S, 1, 0)};  // 4: a car parked for good
	const TWrongStatic w = wrongStaticLandmarks(t, {1, 2, 3, 4, 99});
	EXPECT_EQ(w.map_size, 5u);
	EXPECT_EQ(w.wrong, 2u);
	EXPECT_EQ(w.unknown, 1u);
	EXPECT_EQ(w.wrong_ids, (std::vector<int32_t>{2, 3}));
}

TEST(ClassMetrics, FromTheShippedClassFile)
{
	// The ID-range rule as a classifier on the shipped highway (its agents always move).
	const auto t =
	    io::readClassGroundTruth(std::string(DYNSLAM_DATASETS_DIR) + "/highway_gt_classes.csv");
	ASSERT_EQ(t.size(), 1552u);
	std::vector<Decision> d;
	std::vector<int64_t> groups;
	std::vector<int32_t> allIds;
	for (const auto& r : t)
	{
		const bool object = r.id >= 100000;
		d.push_back(object ? dM : dS);
		groups.push_back(object ? (r.id - 100000) / 1000 : -1);
		allIds.push_back(r.id);
	}
	const TBinaryScores s = perReadingScores(t, d);
	EXPECT_EQ(s.tp + s.fn, 620u);  // object readings: 1552 - 932 static
	EXPECT_DOUBLE_EQ(s.f1, 1.0);
	EXPECT_DOUBLE_EQ(perTrackScores(t, d).f1, 1.0);
	EXPECT_DOUBLE_EQ(groupingAri(t, groups), 1.0);
	// static_all's map holds every ID: the 10 object features are wrong static landmarks.
	std::sort(allIds.begin(), allIds.end());
	allIds.erase(std::unique(allIds.begin(), allIds.end()), allIds.end());
	const TWrongStatic w = wrongStaticLandmarks(t, allIds);
	EXPECT_EQ(w.wrong, 10u);
	EXPECT_EQ(w.unknown, 0u);
	// Everything decided static: recall 0, precision undefined.
	const TBinaryScores z = perReadingScores(t, std::vector<Decision>(t.size(), dS));
	EXPECT_DOUBLE_EQ(z.recall, 0.0);
	EXPECT_TRUE(std::isnan(z.precision));
}
