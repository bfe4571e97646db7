/** CDynamicKFSLAM2D: landmark fusion (fuse_landmarks_prob; issue 29 item 1; the rule in
 * estimator/landmark_fusion.h, doc/robustness.md "Fusing re-identified landmarks"). After the
 * step's commit, the static landmarks read in the step are tested against their neighbours; a
 * pair that is one point is fused by state surgery through the state helper: the conditioning
 * on m_keep = m_gone (state::condition, a noise-free update on the difference), then `gone`
 * leaves the state (commit's removal, the marginalization). Its last estimate is recorded like
 * a dropped landmark (record_dropped), its ID is read as `keep` from the next step on. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/ekf_steps.h>
#include <dynslam/estimator/state_helper.h>

#include <algorithm>
#include <stdexcept>

namespace dynslam
{
using estimator::Route;

void CDynamicKFSLAM2D::resolveFusedIds()
{
	if (!m_fusion.enabled()) return;
	bool aliased = false;
	for (estimator::TRoutedReading& m : m_routed.readings)
	{
		if (m.route != Route::StaticKnown && m.route != Route::StaticNew) continue;
		const int32_t id = m_fusion.resolve(m.reading.id);
		if (id == m.reading.id || !m_staticBlock.count(id)) continue;
		m.reading.id = id;  // a reading of a fused ID: of the landmark it was fused into
		m.route = Route::StaticKnown;
		aliased = true;
	}
	if (!aliased) return;
	// One reading per landmark and step: a second one of the same landmark (both IDs of a fused
	// pair read in one step) is skipped and counted.
	std::vector<int32_t>& used = m_idScratch;
	used.clear();
	for (estimator::TRoutedReading& m : m_routed.readings)
	{
		if (m.route != Route::StaticKnown && m.route != Route::StaticNew) continue;
		const auto it = std::lower_bound(used.begin(), used.end(), m.reading.id);
		if (it != used.end() && *it == m.reading.id)
		{
			m.route = Route::Skip;
			++m_report.skipped_fused_duplicate;
			continue;
		}
		used.insert(it, m.reading.id);
	}
}

void CDynamicKFSLAM2D::forgetStatic(int32_t id)
{
	m_drop.forget(id);
	m_fusion.forget(id);
}

void CDynamicKFSLAM2D::fuseLandmarks()
{
	if (!m_fusion.enabled()) return;
	const auto x = m_xkk.asEigen();
	const auto mean = [&](size_t b)
	{
		const int k = m_layout.first(b);
		return Eigen::Vector2d(x[k], x[k + 1]);
	};
	// The landmarks read in this step (known and new) still in the state.
	std::vector<int32_t> read;
	for (const estimator::TRoutedReading& m : m_routed.readings)
	{
		if (m.route != Route::StaticKnown && m.route != Route::StaticNew) continue;
		const auto it = m_staticBlock.find(m.reading.id);
		if (it == m_staticBlock.end()) continue;
		m_fusion.noteRead(m.reading.id, m_step, mean(it->second));
		read.push_back(m.reading.id);
	}
	const ekf::CSquareBuffer& buf = m_cov;
	const auto d2 = [&](int32_t a, int32_t b)
	{
		return estimator::fusionDistance2(x, buf.view(), m_layout.indices(m_staticBlock.at(a)),
		                                  m_layout.indices(m_staticBlock.at(b)));
	};
	const std::vector<estimator::TFusionPair> pairs = m_fusion.decide(read, d2);
	if (pairs.empty()) return;
	TPending plan;
	for (estimator::TFusionPair f : pairs)
	{
		const size_t bk = m_staticBlock.at(f.keep), bg = m_staticBlock.at(f.gone);
		const std::vector<int> ik = m_layout.indices(bk), ig = m_layout.indices(bg);
		TStaticLandmarkEstimate e;  // gone's last estimate, recorded as a drop is
		e.id = f.gone;
		e.mean = mean(bg);
		e.cov = ekf::marginal(buf.view(), ig);
		e.in_state = false;
		{
			auto xw = m_xkk.asEigen();
			auto P = cov();
			estimator::state::condition(xw, P, ik, ig);
		}
		f.step = m_step;
		if (m_drop.record())
		{
			m_droppedStatic.push_back(e);
			m_fusions.push_back(f);
		}
		// keep was read whenever gone was; gone's ID and its aliases are read as keep.
		const int lastGone = m_drop.lastSeen(f.gone, -1);
		if (lastGone > m_drop.lastSeen(f.keep, -1)) m_drop.noteSeen(f.keep, lastGone);
		m_drop.forget(f.gone);
		m_fusion.fused(f.keep, f.gone, mean(bk));
		plan.remove.push_back(bg);
		++m_report.fused_static;
	}
	commit(plan);  // the fused landmarks leave the state (marginalized)
}
}  // namespace dynslam
