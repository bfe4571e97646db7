/** eval::clearMot and eval::samota (mot_metrics.h) on hand-computed cases. Every number is
 * derived in the comments from the definitions: CLEAR MOT (Bernardin & Stiefelhagen 2008):
 * mota = 1 - (fn + fp + ids) / gt, motp = mean distance (or IoU) of the matches, a mismatch
 * when an object's new match contradicts its last one; frag (Li et al. 2009); sMOTA_r = max(0,
 * 1 - (ids + fp + fn - (1 - r) gt) / (r gt)) and sAMOTA = mean over r (Weng et al. 2020). */
#include <dynslam/eval/mot_metrics.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace dynslam::eval;

namespace
{
TMotObject car(int id, double x, double y = 0, double score = 1)
{
	return {id, "Car", {x, y, 0, 4, 2}, score};
}

TMotOptions byDistance()
{
	TMotOptions o;
	o.criterion = EMotCriterion::CentreDistance;
	return o;
}
}  // namespace

TEST(ClearMot, IdSwitch)
{
	// o1 at 0 in three frames; h1 in frames 0, 1; h2 in frame 2. Frames 0, 1 match (o1, h1);
	// frame 2 matches (o1, h2), which contradicts (o1, h1): ids 1. gt 3, tp 3:
	// mota = 1 - 1/3; motp 0 (exact positions)
	std::vector<TMotFrame> f(3);
	for (auto& fr : f) fr.truth = {car(1, 0)};
	f[0].hyp = {car(1, 0)};
	f[1].hyp = {car(1, 0)};
	f[2].hyp = {car(2, 0)};
	const TMotCounts c = clearMot(f, byDistance());
	EXPECT_EQ(c.gt, 3u);
	EXPECT_EQ(c.tp, 3u);
	EXPECT_EQ(c.ids, 1u);
	EXPECT_EQ(c.fp + c.fn + c.frag, 0u);
	EXPECT_NEAR(c.mota, 2.0 / 3.0, 1e-12);
	EXPECT_NEAR(c.motp, 0, 1e-12);
	// the same ID after a gap of the hypothesis is no switch, but a fragmentation (below)
}

TEST(ClearMot, FragmentationAndMiss)
{
	// o1 in frames 0-3, h1 in frames 0, 1, 3: frame 2 is a miss (fn 1); matched again in
	// frame 3 by the kept mapping (o1, h1): ids 0, frag 1. mota = 1 - 1/4 = 0.75
	std::vector<TMotFrame> f(4);
	for (auto& fr : f) fr.truth = {car(1, 0)};
	f[0].hyp = f[1].hyp = f[3].hyp = {car(1, 0.5)};
	TMotCounts c = clearMot(f, byDistance());
	EXPECT_EQ(c.tp, 3u);
	EXPECT_EQ(c.fn, 1u);
	EXPECT_EQ(c.ids, 0u);
	EXPECT_EQ(c.frag, 1u);
	EXPECT_EQ(c.fp, 0u);
	EXPECT_NEAR(c.mota, 0.75, 1e-12);
	EXPECT_NEAR(c.motp, 0.5, 1e-12);
	// o1 not annotated in frame 2 (and no hypothesis): no miss, no interruption; gt 3, mota 1
	f[2].truth.clear();
	c = clearMot(f, byDistance());
	EXPECT_EQ(c.gt, 3u);
	EXPECT_EQ(c.fn + c.frag + c.ids + c.fp, 0u);
	EXPECT_NEAR(c.mota, 1, 1e-12);
	// missed in its first frames only: not an interruption of a tracked object (frag 0)
	std::vector<TMotFrame> g(3);
	for (auto& fr : g) fr.truth = {car(1, 0)};
	g[2].hyp = {car(1, 0)};
	c = clearMot(g, byDistance());
	EXPECT_EQ(c.fn, 2u);
	EXPECT_EQ(c.frag, 0u);
}

TEST(ClearMot, FalsePositiveAndClass)
{
	// o1 at 0; h1 at 0.5 matches, h2 at 10 is too far: fp 1, mota = 1 - 1/1 = 0, motp 0.5.
	// A pedestrian hypothesis on top of the car matches nothing (classes differ): fp 2
	std::vector<TMotFrame> f(1);
	f[0].truth = {car(1, 0)};
	f[0].hyp = {car(1, 0.5), car(2, 10)};
	TMotCounts c = clearMot(f, byDistance());
	EXPECT_EQ(c.tp, 1u);
	EXPECT_EQ(c.fp, 1u);
	EXPECT_NEAR(c.mota, 0, 1e-12);
	EXPECT_NEAR(c.motp, 0.5, 1e-12);
	f[0].hyp.push_back({3, "Pedestrian", {0, 0, 0, 0.8, 0.6}, 1});
	c = clearMot(f, byDistance());
	EXPECT_EQ(c.fp, 2u);
	EXPECT_NEAR(c.mota, -1, 1e-12);
	// per class: the pedestrian alone is one false positive with no truth (mota NaN)
	c = clearMot(selectClass(f, "Pedestrian"), byDistance());
	EXPECT_EQ(c.fp, 1u);
	EXPECT_EQ(c.gt, 0u);
	EXPECT_TRUE(std::isnan(c.mota));
	EXPECT_EQ(clearMot(selectClass(f, "Car"), byDistance()).fp, 1u);
}

TEST(ClearMot, ThresholdsBothSides)
{
	// centre distance <= 2 m: 2.0 matches, 2.001 does not (then fn 1 and fp 1)
	std::vector<TMotFrame> f(1);
	f[0].truth = {car(1, 0)};
	f[0].hyp = {car(1, 2.0)};
	EXPECT_EQ(clearMot(f, byDistance()).tp, 1u);
	f[0].hyp = {car(1, 2.001)};
	TMotCounts c = clearMot(f, byDistance());
	EXPECT_EQ(c.tp, 0u);
	EXPECT_EQ(c.fn, 1u);
	EXPECT_EQ(c.fp, 1u);
	// BEV IoU >= 0.25: 4 x 2 boxes shifted by d along the length have IoU (4 - d) / (4 + d),
	// 0.25 at d = 2.4; d = 2.39: 0.2505, d = 2.41: 0.2495
	TMotOptions o;  // default: BevIoU, 0.25
	f[0].hyp = {car(1, 2.39)};
	c = clearMot(f, o);
	EXPECT_EQ(c.tp, 1u);
	EXPECT_NEAR(c.motp, 1.61 / 6.39, 1e-12);  // MOTP under IoU: the mean IoU of the matches
	f[0].hyp = {car(1, 2.41)};
	EXPECT_EQ(clearMot(f, o).tp, 0u);
	// IoU criterion: a hypothesis 1 m off matches with IoU 3/5
	f[0].hyp = {car(1, 1.0)};
	EXPECT_NEAR(clearMot(f, o).motp, 0.6, 1e-12);
}

TEST(ClearMot, PersistenceRule)
{
	// frame 0: o1 at 0, h1 at 1.5: matched. Frame 1: h1 still at 1.5 (valid) and h2 at 0.1.
	// Step 1 keeps (o1, h1) although h2 is closer: ids 0, h2 fp. tp 2, motp 1.5
	std::vector<TMotFrame> f(2);
	f[0].truth = f[1].truth = {car(1, 0)};
	f[0].hyp = {car(1, 1.5)};
	f[1].hyp = {car(1, 1.5), car(2, 0.1)};
	TMotCounts c = clearMot(f, byDistance());
	EXPECT_EQ(c.ids, 0u);
	EXPECT_EQ(c.fp, 1u);
	EXPECT_EQ(c.tp, 2u);
	EXPECT_NEAR(c.motp, 1.5, 1e-12);
	// h1 moves to 2.5 (no longer valid): the Hungarian step takes h2, a mismatch; h1 is fp
	f[1].hyp = {car(1, 2.5), car(2, 0.1)};
	c = clearMot(f, byDistance());
	EXPECT_EQ(c.ids, 1u);
	EXPECT_EQ(c.fp, 1u);
	EXPECT_NEAR(c.mota, 1 - 2.0 / 2.0, 1e-12);
	// the mapping survives a frame where o1 is missed: frame 1 has no hypothesis, frame 2 has
	// h1 again (valid) and h2 closer: (o1, h1) kept, ids 0, frag 1
	std::vector<TMotFrame> g(3);
	for (auto& fr : g) fr.truth = {car(1, 0)};
	g[0].hyp = {car(1, 1.5)};
	g[2].hyp = {car(1, 1.5), car(2, 0.1)};
	c = clearMot(g, byDistance());
	EXPECT_EQ(c.ids, 0u);
	EXPECT_EQ(c.frag, 1u);
	EXPECT_EQ(c.fp, 1u);
}

TEST(ClearMot, BadInput)
{
	std::vector<TMotFrame> f(1);
	f[0].truth = {car(1, 0), car(1, 5)};
	EXPECT_THROW(clearMot(f, byDistance()), std::invalid_argument);
	f[0].truth = {car(1, 0)};
	f[0].hyp = {car(4, 0), car(4, 5)};
	EXPECT_THROW(clearMot(f, byDistance()), std::invalid_argument);
	f[0].hyp = {car(4, 0)};
	TMotOptions o;
	o.min_iou = 0;
	EXPECT_THROW(clearMot(f, o), std::invalid_argument);
	o = byDistance();
	o.max_distance = -1;
	EXPECT_THROW(clearMot(f, o), std::invalid_argument);
	o = TMotOptions();
	o.recall_levels = 0;
	EXPECT_THROW(samota(f, o), std::invalid_argument);
}

TEST(Samota, ToySequence)
{
	// o1 at 0 in frames 0-3; h1 in frames 0, 1, 2 with scores 4, 3, 2 (frame 3 missed); a
	// false positive h9 at 10 m in frame 1, score 2.5. gt 4; matched scores of the full run
	// {4, 3, 2}. L = 4:
	// r = 1/4: ceil(1) = 1st score 4: keep h1@0: tp 1, fn 3, fp 0: 1 - (3 - 3)/1 = 1
	// r = 2/4: 2nd score 3: h1@0,1: fn 2, fp 0: 1 - (2 - 2)/2 = 1
	// r = 3/4: 3rd score 2: h1@0,1,2 and h9 (2.5): fn 1, fp 1: 1 - (2 - 1)/3 = 2/3
	// r = 1: needs 4 matches, the full run has 3: 0
	// sAMOTA = (1 + 1 + 2/3 + 0) / 4 = 2/3; the full run's mota = 1 - (1 + 1)/4 = 0.5
	std::vector<TMotFrame> f(4);
	for (auto& fr : f) fr.truth = {car(1, 0)};
	f[0].hyp = {car(1, 0.2, 0, 4)};
	f[1].hyp = {car(1, 0.2, 0, 3), car(9, 10, 0, 2.5)};
	f[2].hyp = {car(1, 0.2, 0, 2)};
	TMotOptions o = byDistance();
	o.recall_levels = 4;
	const TSamota s = samota(f, o);
	ASSERT_EQ(s.smota.size(), 4u);
	EXPECT_NEAR(s.smota[0], 1, 1e-12);
	EXPECT_NEAR(s.smota[1], 1, 1e-12);
	EXPECT_NEAR(s.smota[2], 2.0 / 3.0, 1e-12);
	EXPECT_EQ(s.smota[3], 0);
	EXPECT_TRUE(std::isnan(s.threshold[3]));
	EXPECT_EQ(s.threshold[1], 3);
	EXPECT_NEAR(s.samota, 2.0 / 3.0, 1e-12);
	EXPECT_NEAR(clearMot(f, o).mota, 0.5, 1e-12);
	// the clamp at 0: with 3 false positives at level 1/4 (score 5 each, kept at threshold
	// 4): 1 - (3 + 3 - 3)/1 < 0 -> 0
	f[3].hyp = {car(5, 20, 0, 5), car(6, 30, 0, 5), car(7, 40, 0, 5)};
	EXPECT_EQ(samota(f, o).smota[0], 0);
}
