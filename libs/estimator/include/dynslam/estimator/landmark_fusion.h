#pragma once
/** @file landmark_fusion.h
 * Landmark fusion (issue 29 item 1; doc/robustness.md "Fusing re-identified landmarks"): two
 * static landmarks of the state are one point when the test on their joint estimate passes,
 *   d = m_i - m_j,  S = P_ii + P_jj - P_ij - P_ji,  d^T S^-1 d <= chi2_2(p)
 * (p = fuse_landmarks_prob). The fusion itself is state surgery through the state helper:
 * state::condition on m_i = m_j (a noise-free update on the difference), then j leaves the
 * state; j's ID is routed to i from then on (the alias table here).
 *
 * The rule (CLandmarkFusion::decide), checked for the landmarks read in this step (known or new)
 * only, so its cost does not grow with the map:
 *  1. neighbours: the landmarks registered in the 3 x 3 grid cells (side kCell) around a
 *     landmark's cell (the cell of its mean when it was last read or initialised);
 *  2. two IDs read in one common step are two points (the sensor reports one reading per point
 *     and step): only landmarks whose reading intervals [first, last] are disjoint are
 *     compared (a track break ends the old ID before the new one starts);
 *  3. compatible: the test above passes (d2 <= threshold);
 *  4. unambiguous: i and j are fused only if each is the other's single compatible neighbour;
 *     the older one (earlier first reading, then the lower ID) is kept.
 * The decisions of a step are taken on the state before its first fusion; the pairs are
 * disjoint (rule 4). Pure Eigen. */
#include <dynslam/core/ekf_steps.h>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace dynslam::estimator
{
/** chi2_2(p), the 2-dof quantile of fuse_landmarks_prob p. Throws std::invalid_argument unless
 * 0 < p < 1. */
double fusionThreshold(double p);

/** d^T S^-1 d for d = x[a] - x[b], S = P_aa + P_bb - P_ab - P_ba (a, b: the 2 storage indices
 * of each landmark); +inf if S is not positive definite. */
double fusionDistance2(const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const ekf::RowMatrixXd>& P, const std::vector<int>& a,
                       const std::vector<int>& b);

struct TFusionPair
{
	int32_t keep = -1;  ///< the landmark that stays (the older one)
	int32_t gone = -1;  ///< the landmark fused into it (leaves the state, its ID aliased)
	double d2 = 0;      ///< the test statistic
	int step = -1;      ///< the step of the fusion (set by the filter)
};

class CLandmarkFusion
{
public:
	static constexpr double kCell = 5.0;  ///< [m] side of a grid cell (the neighbourhood: 3 x 3)
	CLandmarkFusion() = default;
	/** p = fuse_landmarks_prob: 0 = off, else in (0, 1) (std::invalid_argument otherwise). */
	explicit CLandmarkFusion(double p, double cell = kCell);
	bool enabled() const { return m_threshold > 0; }
	double threshold() const { return m_threshold; }
	void clear();
	/** Landmark `id` of the state was read (or initialised) at `step`, its mean now p: its
	 * reading interval grows to `step`, it is registered in p's cell. */
	void noteRead(int32_t id, int step, const Eigen::Vector2d& p);
	/** Landmark `id` left the state: out of the grid; the IDs fused into it are forgotten (read
	 * again, they start a landmark of their own). */
	void forget(int32_t id);
	/** The landmark that ID `id` is read as: the one it was fused into, else itself. */
	int32_t resolve(int32_t id) const
	{
		const auto it = m_alias.find(id);
		return it == m_alias.end() ? id : it->second;
	}
	/** The pairs to fuse among the landmarks `read` (this step) and their neighbours, by the
	 * rule of the file comment; d2(a, b) is the test statistic of landmarks a and b (their joint
	 * estimate). In the order of `read`. */
	std::vector<TFusionPair> decide(const std::vector<int32_t>& read,
	                                const std::function<double(int32_t, int32_t)>& d2) const;
	/** `gone` was fused into `keep` (whose mean is now p): gone's ID and the IDs fused into it
	 * are read as keep from now on, keep's reading interval spans both, gone leaves the grid. */
	void fused(int32_t keep, int32_t gone, const Eigen::Vector2d& p);
	/** Bookkeeping sizes (landmarks registered, IDs aliased): bounded by the state. */
	size_t registered() const { return m_tracks.size(); }
	size_t aliased() const { return m_alias.size(); }

private:
	struct TTrack
	{
		int first = 0, last = 0;
		int64_t cell = 0;
	};
	int64_t cellOf(const Eigen::Vector2d& p) const;
	void unregister(int32_t id, int64_t cell);
	/** The compatible neighbours of landmark `id` (rules 1-3). */
	std::vector<std::pair<int32_t, double>> compatible(
	    int32_t id, const std::function<double(int32_t, int32_t)>& d2) const;
	double m_threshold = 0;  ///< 0: off
	double m_cell = kCell;
	std::unordered_map<int32_t, TTrack> m_tracks;
	std::unordered_map<int64_t, std::vector<int32_t>> m_grid;       ///< cell -> landmarks
	std::unordered_map<int32_t, int32_t> m_alias;                   ///< fused ID -> landmark
	std::unordered_map<int32_t, std::vector<int32_t>> m_aliasesOf;  ///< landmark -> fused IDs
};
}  // namespace dynslam::estimator
