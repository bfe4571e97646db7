/** Readings with ID -1 under feature_labels = classify (unknown_id_association.h). */
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/unknown_id_association.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <tuple>

namespace dynslam::estimator
{
void TUnknownIdParams::validate() const
{
	const auto oneOf = [](const std::string& v, const char* key, const char* a, const char* b)
	{
		if (v != a && v != b)
			throw std::invalid_argument(std::string(key) + " = " + v + ": must be " + a + " or " +
			                            b);
	};
	oneOf(method, "classify_assoc_method", "assocNN", "assocJCBB");
	oneOf(metric, "classify_assoc_metric", "metricMaha", "metricML");
	oneOf(IC_metric, "classify_assoc_IC_metric", "metricMaha", "metricML");
	const auto prob = [](double p, const char* key)
	{
		if (!(p > 0 && p < 1))
			throw std::invalid_argument(std::string(key) + " = " + std::to_string(p) +
			                            ": must be a probability in (0, 1)");
	};
	prob(IC_chi2_thres, "classify_assoc_IC_chi2_thres");
	prob(moving_gate, "classify_assoc_moving_gate");
	if (!(max_step >= 0) || !std::isfinite(max_step))
		throw std::invalid_argument("classify_assoc_max_step must be >= 0 (0: off)");
	if (!std::isfinite(IC_ml_threshold))
		throw std::invalid_argument("classify_assoc_IC_ml_threshold must be finite");
}

CUnknownIdResolver::CUnknownIdResolver(const TUnknownIdParams& p) : m_p(p) { m_p.validate(); }

void CUnknownIdResolver::reset()
{
	m_movers.clear();
	m_increments.clear();
	m_firstIncrement = m_predicts = 0;
	m_compactAt = 256;
	m_next = kFirstResolvedId;
}

void CUnknownIdResolver::carry(TMover& m) const
{
	for (; m.carried < m_predicts; ++m.carried)
	{
		const TStaticMotion& inc = m_increments[m.carried - m_firstIncrement];
		// The point moves by vel (previous frame), then the robot by u.
		TPoint2 moved = m.last;
		if (m.has_vel) moved.p += m.vel;
		m.last = predictStatic(moved, inc);
		m.vel = inc.Rt * m.vel;
	}
}

void CUnknownIdResolver::predict(const Eigen::Vector3d& u, const Eigen::Matrix3d& U)
{
	m_increments.emplace_back(u, U);
	++m_predicts;
	if (m_increments.size() < m_compactAt) return;
	// Forget the increments every track has had. Not by carrying every track here (that costs
	// the number of tracks ever read, per step on average: issue 29); the check itself visits
	// every track, so it runs when the list has doubled since the last one.
	size_t oldest = m_predicts;
	for (const auto& [id, m] : m_movers) oldest = std::min(oldest, m.carried);
	m_increments.erase(m_increments.begin(),
	                   m_increments.begin() + std::ptrdiff_t(oldest - m_firstIncrement));
	m_firstIncrement = oldest;
	m_compactAt = std::max<size_t>(256, 2 * m_increments.size());
}

TTrackPrediction CUnknownIdResolver::predictionOf(int32_t id, TMover& m, int step,
                                                  double motion_std) const
{
	carry(m);
	TTrackPrediction t;
	t.target.id = id;
	t.target.pred = m.last;
	t.gap = std::max(1, step - m.last_step);
	t.target.pred.C += Eigen::Matrix2d::Identity() * motion_std * motion_std * t.gap;
	t.has_vel = m.has_vel;
	t.vel = m.vel;
	return t;
}

std::vector<TTrackPrediction> CUnknownIdResolver::predictions(int step, double motion_std) const
{
	std::vector<TTrackPrediction> out;
	for (auto& [id, m] : m_movers) out.push_back(predictionOf(id, m, step, motion_std));
	return out;
}

std::optional<TTrackPrediction> CUnknownIdResolver::prediction(int32_t id, int step,
                                                               double motion_std) const
{
	const auto it = m_movers.find(id);
	if (it == m_movers.end()) return std::nullopt;
	return predictionOf(id, it->second, step, motion_std);
}

bool CUnknownIdResolver::velocityWith(int32_t id, const TPoint2& z, int step,
                                      Eigen::Vector2d& vel) const
{
	const auto it = m_movers.find(id);
	if (it == m_movers.end()) return false;
	TMover& m = it->second;
	carry(m);
	const int g = std::max(1, step - m.last_step);
	const Eigen::Vector2d prev =
	    m.has_vel ? Eigen::Vector2d(m.last.p - double(g) * m.vel) : m.last.p;
	vel = (z.p - prev) / double(g);
	return true;
}

void CUnknownIdResolver::observe(int32_t id, const TPoint2& z, int step)
{
	auto it = m_movers.find(id);
	if (it == m_movers.end())
	{
		m_movers[id] = TMover{z, Eigen::Vector2d::Zero(), step, false, m_predicts};
		return;
	}
	TMover& m = it->second;
	carry(m);
	const int g = std::max(1, step - m.last_step);
	// m.last is the previous reading carried through g steps, each adding the (rotated) velocity:
	// exactly g * vel in the current frame. Undo it to get the displacement per step.
	const Eigen::Vector2d prev =
	    m.has_vel ? Eigen::Vector2d(m.last.p - double(g) * m.vel) : m.last.p;
	m.vel = (z.p - prev) / double(g);
	m.has_vel = true;
	m.last = z;
	m.last_step = step;
}

TResolvedIds CUnknownIdResolver::resolve(const std::vector<int32_t>& ids,
                                         const std::vector<TPoint2>& z,
                                         const std::vector<TAssocTarget>& statics,
                                         const std::vector<TAssocTarget>& moving,
                                         const std::vector<TTrackPrediction>& once)
{
	if (ids.size() != z.size()) throw std::invalid_argument("CUnknownIdResolver::resolve: sizes");
	TResolvedIds r;
	r.ids = ids;
	std::vector<size_t> unknown;
	for (size_t i = 0; i < ids.size(); ++i)
		if (ids[i] == -1) unknown.push_back(i);
	if (unknown.empty()) return r;
	std::set<int32_t> taken;  // one reading per track and step, across the stages
	// 1) static: MRPT's association (injected).
	if (!statics.empty() && m_static)
	{
		std::vector<Eigen::Vector2d> obs;
		for (size_t i : unknown) obs.push_back(z[i].p);
		const std::vector<int> a = m_static(obs, statics);
		if (a.size() != obs.size())
			throw std::logic_error("CUnknownIdResolver: static association returned a wrong size");
		for (size_t k = 0; k < unknown.size(); ++k)
			if (a[k] >= 0 && size_t(a[k]) < statics.size() &&
			    !taken.count(statics[size_t(a[k])].id))
			{
				taken.insert(statics[size_t(a[k])].id);
				r.ids[unknown[k]] = statics.at(size_t(a[k])).id;
				++r.to_static;
			}
	}
	// 2) moving: nearest neighbour inside the gate, smallest distance first, one to one.
	const double gate = chiSquareQuantile(m_p.moving_gate, 2);
	std::vector<std::tuple<double, size_t, size_t>> pairs;  // (d2, reading, target)
	for (size_t i : unknown)
	{
		if (r.ids[i] != -1) continue;
		for (size_t j = 0; j < moving.size(); ++j)
		{
			const Eigen::Vector2d nu = z[i].p - moving[j].pred.p;
			const double d2 = nu.dot((moving[j].pred.C + z[i].C).inverse() * nu);
			if (d2 <= gate) pairs.emplace_back(d2, i, j);
		}
	}
	std::sort(pairs.begin(), pairs.end());
	std::vector<bool> used(moving.size(), false);
	for (const auto& [d2, i, j] : pairs)
	{
		if (r.ids[i] != -1 || used[j] || taken.count(moving[j].id)) continue;
		used[j] = true;
		taken.insert(moving[j].id);
		r.ids[i] = moving[j].id;
		++r.to_moving;
	}
	// 3) second sightings: candidates seen once, nearest first within max_step * gap.
	pairs.clear();
	for (size_t i : unknown)
	{
		if (r.ids[i] != -1 || !(m_p.max_step > 0)) continue;
		for (size_t j = 0; j < once.size(); ++j)
		{
			const double d = (z[i].p - once[j].target.pred.p).norm();
			if (d <= m_p.max_step * once[j].gap) pairs.emplace_back(d, i, j);
		}
	}
	std::sort(pairs.begin(), pairs.end());
	std::vector<bool> usedOnce(once.size(), false);
	for (const auto& [d, i, j] : pairs)
	{
		if (r.ids[i] != -1 || usedOnce[j] || taken.count(once[j].target.id)) continue;
		usedOnce[j] = true;
		taken.insert(once[j].target.id);
		r.ids[i] = once[j].target.id;
		++r.to_second;
	}
	// 4) new anonymous tracks.
	for (size_t i : unknown)
		if (r.ids[i] == -1)
		{
			r.ids[i] = m_next++;
			++r.new_tracks;
		}
	return r;
}
}  // namespace dynslam::estimator
