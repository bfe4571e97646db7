#pragma once
/** @file effects.h
 * Issue 12's front-end effects applied to one step's readings after their noise was drawn
 * (private to libs/sim; see doc/simulator.md, "Front-end effects"): missed detections, track
 * breaks, anonymous IDs, clutter, and the class ground truth of every reading. */
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/random/RandomGenerators.h>

#include <unordered_map>
#include <vector>

namespace dynslam::sim::detail
{
class CReadingEffects
{
public:
	/** seed: the run's noise seed (the effects use their own generator, see TReadingEffects). */
	CReadingEffects(const io::TGroundTruth& gt, const TScenarioOptions& o, uint32_t seed);

	/** obs holds the true readings of step k (true IDs) in their order; truth one row each
	 * (step, t, id = true_id, class, object, feature set). Drops missed readings, replaces IDs
	 * (breaks, anonymity), appends clutter, sorts by ID when anonymous, sets the final id and
	 * index of each row. A no-op on the readings when no effect is enabled. */
	void apply(size_t k, mrpt::obs::CObservationBearingRange& obs,
	           std::vector<io::TReadingClass>& truth);

	/** The anonymous ID of a true ID (identity when anonymous_ids is off). */
	int32_t initialId(int32_t true_id) const;

private:
	int32_t trackId(int32_t true_id, size_t k);
	int32_t newTrackId(int32_t true_id);
	int32_t clutterId();

	const TScenarioOptions& m_o;
	TReadingEffects m_e;
	mrpt::random::CRandomGenerator m_rng;
	std::unordered_map<int32_t, int32_t> m_anon;  ///< true ID -> anonymous ID
	struct TTrack
	{
		int32_t id = -1;
		long last_seen = -1;
	};
	std::unordered_map<int32_t, TTrack> m_tracks;  ///< by true ID
	int32_t m_nextAnon = 0, m_nextStatic = 0;
	std::vector<int32_t> m_nextFeature;  ///< per object: next free feature index
};
}  // namespace dynslam::sim::detail
