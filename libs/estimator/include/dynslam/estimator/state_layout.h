#pragma once
/** @file state_layout.h
 * The typed state of the estimator core and how it is stored in MRPT's fixed-size Kalman
 * filter (doc/state-layout.md). After the ego pose (3 entries) come typed blocks: a static
 * landmark, an object feature at its first sighting (f_0) or now (f_t), an object pose (3-dof
 * or translation-only), and room for more kinds (an object velocity). MRPT's
 * CKalmanFilterCapable<3,2,2,3> stores 2-dof slots, so a block of d entries occupies
 * ceil(d/2) consecutive slots; an odd-sized block ends with a pad (mean 0, variance 1, zero
 * cross-covariance) that no model touches. This class is the one place that maps blocks to
 * storage indices: "an object pose is slot A plus an optional slot B" is never rebuilt from
 * adjacency. */
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dynslam::estimator
{
enum class BlockKind : uint8_t
{
	StaticLandmark,  ///< f = (x, y)
	ObjectFeature0,  ///< feature of a moving object at its first sighting (time 0)
	ObjectFeatureT,  ///< feature of a moving object now (time t)
	ObjectPose,      ///< xi_t = (dx, dy, dtheta), or (dx, dy) for one-feature objects
	/** The velocity block of an object-centric motion model: its first entries are the velocity
	 * (vx, vy[, omega]), as many as the pose has; further ones are the model's (ca: the
	 * acceleration), read by no one else (doc/state-layout.md). */
	ObjectVelocity,
	OdometryBias,  ///< (b_w) or (b_w, s): odometry bias (dynslam/core/models/odometry_bias.h)
	/** Compressed EKF only (compressed_state.h): two columns of the accumulated cross-covariance
	 * of the active state with the passive one (`object` = the level, `feature` = the pair). */
	Compressed
};
const char* toString(BlockKind k);

struct TBlock
{
	BlockKind kind = BlockKind::StaticLandmark;
	int32_t id = -1;       ///< landmark / feature ID (features), -1 otherwise
	int32_t object = -1;   ///< the object (object blocks)
	int32_t feature = -1;  ///< the feature index within the object (features)
	int step = -1;         ///< step of a pose or of a time-t feature; creation step otherwise
	int dim = 2;           ///< entries (without the pad)
	/** Creation order: CPaddedLayout::append numbers the blocks it adds, so a layout is in
	 * ascending order (the compressed EKF's global update restores it, compressed_state.h). */
	uint64_t seq = 0;
	/** 2-dof storage slots it occupies. */
	int slots() const { return (dim + 1) / 2; }
};

class CPaddedLayout
{
public:
	static constexpr int kEgoDim = 3;
	void clear();
	size_t size() const { return m_blocks.size(); }
	bool empty() const { return m_blocks.empty(); }
	const TBlock& operator[](size_t b) const { return m_blocks[b]; }
	const std::vector<TBlock>& blocks() const { return m_blocks; }
	/** Appends a block (dim 1..6) at the end of the storage, numbered after every block
	 * appended before (TBlock::seq). */
	void append(const TBlock& b);
	/** Appends a block keeping its number (later appends are numbered after it). */
	void appendNumbered(const TBlock& b);
	/** Storage index of block b's first entry. */
	int first(size_t b) const { return m_first[b]; }
	/** Storage indices of block b's entries (dim of them, no pad). */
	std::vector<int> indices(size_t b) const;
	/** MRPT's landmark index (2-dof slot) of block b's first slot. */
	size_t slotOf(size_t b) const { return size_t(m_first[b] - kEgoDim) / 2; }
	/** The block that occupies 2-dof slot s (MRPT's landmark index). */
	size_t blockAtSlot(size_t s) const { return m_blockAtSlot.at(s); }
	size_t numSlots() const { return m_blockAtSlot.size(); }
	/** Storage size: the ego plus two entries per slot. */
	int storageDim() const { return kEgoDim + 2 * int(m_blockAtSlot.size()); }
	/** Storage indices of the pads, ascending. */
	std::vector<int> padIndices() const;
	/** Storage indices kept when the flagged blocks are removed (ego included, ascending). */
	std::vector<int> keptStorage(const std::vector<bool>& remove) const;
	/** Sets the step of block b (an object pose predicted in place by a motion model). */
	void setStep(size_t b, int step) { m_blocks.at(b).step = step; }
	/** State surgery (doc/results/classification.md): static landmark block b becomes the time-0
	 * feature `feature` of object `object`, in place (same storage, ID, creation step and number).
	 * Throws std::logic_error if block b is not a static landmark. */
	void convertToObjectFeature0(size_t b, int32_t object, int32_t feature);
	/** Merge (classify_merge_linked): time-0 feature block b becomes feature `feature` of object
	 * `object` (its entries rewritten by the caller). Throws std::logic_error if block b is not
	 * an ObjectFeature0. */
	void reassignObjectFeature0(size_t b, int32_t object, int32_t feature);
	/** Removes the flagged blocks (one flag per block); the others keep their order. */
	void removeBlocks(const std::vector<bool>& remove);

private:
	std::vector<TBlock> m_blocks;
	std::vector<int> m_first;
	std::vector<size_t> m_blockAtSlot;
	uint64_t m_nextSeq = 0;
};
}  // namespace dynslam::estimator
