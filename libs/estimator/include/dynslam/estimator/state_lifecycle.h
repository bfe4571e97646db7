#pragma once
/** @file state_lifecycle.h
 * Seam 4 of the estimator core (doc/architecture.md): how the state is stored between steps,
 * independent of how it is updated. The EKF asks its lifecycle, at the start of a step, whether
 * the working state must be brought up to date (expand), and at the end of a step whether
 * entries leave it (compressIfDue); getters of the whole state read an expanded copy
 * (expandedCopy) and leave the working state as it is. Every update engine composes with
 * every lifecycle as long as it updates the (x, P) it is given touching only the readings'
 * entries and the ego (IUpdateEngine::updatesGivenState()).
 *
 * Implementations: CFullStateLifecycle ("full": the whole state is the working state, every
 * hook a no-op) and CCompressedLifecycle ("compressed", static_update = compressed: the exact
 * compressed EKF of compressed_state.h: static landmarks unseen for `passive_after` steps leave
 * the working state, `batch` of them at a time, and are brought up to date exactly when one is
 * read again, is due to be dropped, or the whole state is read). */
#include <dynslam/estimator/compressed_state.h>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace dynslam::estimator
{
class IStateLifecycle
{
public:
	virtual ~IStateLifecycle() = default;
	virtual std::string name() const = 0;
	/** Forgets everything held out of the state (the filter's reset). */
	virtual void reset() = 0;
	/** Whether it ever rewrites the working state's storage (takes entries out of it): then the
	 * update engine must update the state it is given (IUpdateEngine::updatesGivenState()). */
	virtual bool rewritesStorage() const = 0;
	/** Whether the working state holds compressed entries now (its getters need an expansion). */
	virtual bool holdsPassive() const = 0;
	/** Whether static landmark `id` is held out of the working state. */
	virtual bool isPassive(int32_t id) const = 0;
	/** Static landmarks held out of the working state. */
	virtual size_t passiveCount() const = 0;
	/** Start of a step: whether the working state must be expanded before the step, given the
	 * IDs read in it and due(id, step of its block) = "the landmark is due to be dropped". */
	virtual bool expansionNeeded(const std::vector<int32_t>& readIds,
	                             const std::function<bool(int32_t, int)>& due) const = 0;
	/** The global update in place: (x, P, layout) become the whole state; nothing is held out
	 * afterwards. A no-op when nothing is held out. */
	virtual void expand(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout) = 0;
	/** The whole state of the working state (x, P, layout) into (xo, Po, lo), changing neither
	 * the working state nor what is held out. */
	virtual void expandedCopy(const Eigen::Ref<const Eigen::VectorXd>& x,
	                          const Eigen::Ref<const ekf::RowMatrixXd>& P,
	                          const CPaddedLayout& layout, Eigen::VectorXd& xo,
	                          ekf::RowMatrixXd& Po, CPaddedLayout& lo) const = 0;
	/** End of a step: takes the entries that are due out of the working state (x, P, layout),
	 * writing the new working state to (xo, Po) and `layout`. unseen(block) = steps since the
	 * static landmark of `block` was last read. False: nothing changed (xo, Po untouched). */
	virtual bool compressIfDue(const Eigen::Ref<const Eigen::VectorXd>& x,
	                           const Eigen::Ref<const ekf::RowMatrixXd>& P, CPaddedLayout& layout,
	                           const std::function<int(const TBlock&)>& unseen, Eigen::VectorXd& xo,
	                           ekf::RowMatrixXd& Po) = 0;
};

/** The whole state is the working state (the default). */
class CFullStateLifecycle final : public IStateLifecycle
{
public:
	std::string name() const override { return "full"; }
	void reset() override {}
	bool rewritesStorage() const override { return false; }
	bool holdsPassive() const override { return false; }
	bool isPassive(int32_t) const override { return false; }
	size_t passiveCount() const override { return 0; }
	bool expansionNeeded(const std::vector<int32_t>&,
	                     const std::function<bool(int32_t, int)>&) const override
	{
		return false;
	}
	void expand(Eigen::VectorXd&, ekf::RowMatrixXd&, CPaddedLayout&) override {}
	void expandedCopy(const Eigen::Ref<const Eigen::VectorXd>& x,
	                  const Eigen::Ref<const ekf::RowMatrixXd>& P, const CPaddedLayout& layout,
	                  Eigen::VectorXd& xo, ekf::RowMatrixXd& Po, CPaddedLayout& lo) const override;
	bool compressIfDue(const Eigen::Ref<const Eigen::VectorXd>&,
	                   const Eigen::Ref<const ekf::RowMatrixXd>&, CPaddedLayout&,
	                   const std::function<int(const TBlock&)>&, Eigen::VectorXd&,
	                   ekf::RowMatrixXd&) override
	{
		return false;
	}
};

/** The exact compressed EKF (compressed_state.h). */
class CCompressedLifecycle final : public IStateLifecycle
{
public:
	/** Throws std::invalid_argument if passive_after < 1 or batch < 1. */
	explicit CCompressedLifecycle(int passive_after = 3, int batch = 8);
	std::string name() const override { return "compressed"; }
	int passiveAfter() const { return m_passiveAfter; }
	int batch() const { return m_batch; }
	void reset() override;
	bool rewritesStorage() const override { return true; }
	bool holdsPassive() const override { return !m_levels.empty(); }
	bool isPassive(int32_t id) const override { return m_passiveStatic.count(id) != 0; }
	size_t passiveCount() const override { return m_passiveStatic.size(); }
	bool expansionNeeded(const std::vector<int32_t>& readIds,
	                     const std::function<bool(int32_t, int)>& due) const override;
	void expand(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout) override;
	void expandedCopy(const Eigen::Ref<const Eigen::VectorXd>& x,
	                  const Eigen::Ref<const ekf::RowMatrixXd>& P, const CPaddedLayout& layout,
	                  Eigen::VectorXd& xo, ekf::RowMatrixXd& Po, CPaddedLayout& lo) const override;
	bool compressIfDue(const Eigen::Ref<const Eigen::VectorXd>& x,
	                   const Eigen::Ref<const ekf::RowMatrixXd>& P, CPaddedLayout& layout,
	                   const std::function<int(const TBlock&)>& unseen, Eigen::VectorXd& xo,
	                   ekf::RowMatrixXd& Po) override;

private:
	int m_passiveAfter, m_batch;
	std::vector<TPassiveLevel> m_levels;     ///< compression levels, oldest first
	std::map<int32_t, int> m_passiveStatic;  ///< passive landmark ID -> its block's step
	int m_nextLevel = 0;
};
}  // namespace dynslam::estimator
