/** The landmark-fusion module (fusion.h). */
#include "fusion.h"

#include <dynslam/core/ekf_steps.h>
#include <dynslam/estimator/state_helper.h>

#include <algorithm>
#include <stdexcept>

namespace dynslam::ekf
{
using estimator::Route;

std::unique_ptr<CLandmarkFusionModule> makeLandmarkFusionModule(TFilterAccess& a)
{
	if (!estimator::CLandmarkFusion(a.options().fuse_landmarks_prob).enabled()) return nullptr;
	if (a.lifecycle().rewritesStorage())
		throw std::invalid_argument(
		    "CDynamicKFSLAM2D: fuse_landmarks_prob needs the full state "
		    "(the state lifecycle " +
		    a.lifecycle().name() + " keeps landmarks out of it)");
	return std::make_unique<CLandmarkFusionModule>(a.options().fuse_landmarks_prob);
}

void CLandmarkFusionModule::afterRoute(TFilterAccess& a)
{
	bool aliased = false;
	for (estimator::TRoutedReading& m : a.routed().readings)
	{
		if (m.route != Route::StaticKnown && m.route != Route::StaticNew) continue;
		const int32_t id = m_fusion.resolve(m.reading.id);
		if (id == m.reading.id || !a.staticBlocks().count(id)) continue;
		m.reading.id = id;  // a reading of a fused ID: of the landmark it was fused into
		m.route = Route::StaticKnown;
		aliased = true;
	}
	if (!aliased) return;
	// One reading per landmark and step: a second one of the same landmark (both IDs of a fused
	// pair read in one step) is skipped and counted.
	std::vector<int32_t>& used = m_used;
	used.clear();
	for (estimator::TRoutedReading& m : a.routed().readings)
	{
		if (m.route != Route::StaticKnown && m.route != Route::StaticNew) continue;
		const auto it = std::lower_bound(used.begin(), used.end(), m.reading.id);
		if (it != used.end() && *it == m.reading.id)
		{
			m.route = Route::Skip;
			++a.report().skipped_fused_duplicate;
			continue;
		}
		used.insert(it, m.reading.id);
	}
}

void CLandmarkFusionModule::afterCommit(TFilterAccess& a)
{
	const auto x = a.mean();
	const estimator::CPaddedLayout& layout = a.layout();
	const std::map<int32_t, size_t>& statics = a.staticBlocks();
	const auto mean = [&](size_t b)
	{
		const int k = layout.first(b);
		return Eigen::Vector2d(x[k], x[k + 1]);
	};
	// The landmarks read in this step (known and new) still in the state.
	std::vector<int32_t> read;
	for (const estimator::TRoutedReading& m : a.routed().readings)
	{
		if (m.route != Route::StaticKnown && m.route != Route::StaticNew) continue;
		const auto it = statics.find(m.reading.id);
		if (it == statics.end()) continue;
		m_fusion.noteRead(m.reading.id, a.step(), mean(it->second));
		read.push_back(m.reading.id);
	}
	const ekf::CSquareBuffer& buf = a.covBuffer();
	const auto d2 = [&](int32_t p, int32_t q)
	{
		return estimator::fusionDistance2(x, buf.view(), layout.indices(statics.at(p)),
		                                  layout.indices(statics.at(q)));
	};
	const std::vector<estimator::TFusionPair> pairs = m_fusion.decide(read, d2);
	if (pairs.empty()) return;
	estimator::CDropPolicy& drop = a.dropPolicy();
	TPending plan;
	for (estimator::TFusionPair f : pairs)
	{
		const size_t bk = statics.at(f.keep), bg = statics.at(f.gone);
		const std::vector<int> ik = layout.indices(bk), ig = layout.indices(bg);
		TStaticLandmarkEstimate e;  // gone's last estimate, recorded as a drop is
		e.id = f.gone;
		e.mean = mean(bg);
		e.cov = ekf::marginal(buf.view(), ig);
		e.in_state = false;
		{
			auto xw = a.mean();
			auto P = a.cov();
			estimator::state::condition(xw, P, ik, ig);
		}
		f.step = a.step();
		if (drop.record())
		{
			a.recordDroppedStatic(e);
			m_fusions.push_back(f);
		}
		// keep was read whenever gone was; gone's ID and its aliases are read as keep.
		const int lastGone = drop.lastSeen(f.gone, -1);
		if (lastGone > drop.lastSeen(f.keep, -1)) drop.noteSeen(f.keep, lastGone);
		drop.forget(f.gone);
		m_fusion.fused(f.keep, f.gone, mean(bk));
		plan.remove.push_back(bg);
		++a.report().fused_static;
	}
	a.commit(plan);  // the fused landmarks leave the state (marginalized)
}
}  // namespace dynslam::ekf
