#pragma once
/** @file state_store.h
 * (Internal to dynslam::ekf.) The state's lifecycle in CDynamicKFSLAM2D: the one caller of the
 * filter's estimator::IStateLifecycle (estimator/state_lifecycle.h; the compressed EKF of
 * static_update = compressed is estimator::CCompressedLifecycle, its math compressed_state.h)
 * and the owner of the whole state's expanded copy.
 *
 * The step runs unchanged on the working state; a lifecycle that rewrites the storage may take
 * entries out of it at the end of a step (endOfStep) and needs them back (the global update)
 * when one is read again or is due to be dropped (startOfStep). Getters of the whole state read
 * an expanded copy (whole(), made on the first read after the working state changed) and leave
 * the working state as it is.
 *
 * Not a capability module (modules/filter_module.h): the getters of the whole state read it in
 * every configuration. The step calls it only when the lifecycle rewrites the storage (active(),
 * set by reset()): with the full lifecycle it costs one flag per step. */
#include <cstdint>
#include <vector>

#include "modules/filter_module.h"

namespace dynslam::ekf
{
/** The whole state while the working state holds compressed entries: an expanded copy. */
struct TWholeState
{
	CDynamicKFSLAM2D::KFVector x;
	CDynamicKFSLAM2D::KFMatrix P;
	estimator::CPaddedLayout layout;
	std::vector<TSlot> slots;
};

class CStateStore
{
public:
	using TStateRef = TFilterView::TStateRef;
	/** The filter's reset (after its lifecycle was reset): forgets the expanded copy; active:
	 * the lifecycle rewrites the working state's storage (IStateLifecycle::rewritesStorage). */
	void reset(bool active);
	/** Whether the step must call startOfStep and endOfStep. */
	bool active() const { return m_active; }
	/** Start of a step: the global update if the lifecycle needs it (a passive landmark is read
	 * in the step or due to be dropped). */
	void startOfStep(TFilterAccess& a);
	/** End of a step: the lifecycle's compression of the entries that are due. */
	void endOfStep(TFilterAccess& a);
	/** The global update of the working state (CDynamicKFSLAM2D::globalUpdate); no-op when
	 * nothing is held out of it. */
	void globalUpdate(TFilterAccess& a);
	/** The whole state: the working state's storage, or the expanded copy when the lifecycle
	 * holds entries out of it. */
	TStateRef whole(const TFilterView& v) const;
	/** The expanded copy of the working state (valid until the working state changes). */
	const TWholeState& expanded(const TFilterView& v) const;

private:
	bool m_active = false;
	mutable TWholeState m_whole;
	mutable bool m_valid = false;
	mutable uint64_t m_version = 0;  ///< TFilterView::stateVersion() of the copy
	std::vector<int32_t> m_ids;      ///< scratch: the IDs read in the step
};
}  // namespace dynslam::ekf
