#include <dynslam/core/chi2.h>
#include <dynslam/estimator/landmark_fusion.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dynslam::estimator
{
double fusionThreshold(double p)
{
	if (!(p > 0 && p < 1))
		throw std::invalid_argument("fuse_landmarks_prob = " + std::to_string(p) +
		                            ": must be a probability in (0, 1) (0 = off)");
	return chi2Quantile(p, 2);
}

double fusionDistance2(const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const ekf::RowMatrixXd>& P, const std::vector<int>& a,
                       const std::vector<int>& b)
{
	const Eigen::Vector2d d(x[a[0]] - x[b[0]], x[a[1]] - x[b[1]]);
	Eigen::Matrix2d S;
	for (int r = 0; r < 2; ++r)
		for (int c = 0; c < 2; ++c)
			S(r, c) = P(a[r], a[c]) + P(b[r], b[c]) - P(a[r], b[c]) - P(b[r], a[c]);
	const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (S + S.transpose()));
	if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
	return d.dot(llt.solve(d));
}

CLandmarkFusion::CLandmarkFusion(double p, double cell) : m_cell(cell)
{
	if (p != 0) m_threshold = fusionThreshold(p);
	if (!(cell > 0)) throw std::invalid_argument("CLandmarkFusion: the cell must be > 0");
}

void CLandmarkFusion::clear()
{
	m_tracks.clear();
	m_grid.clear();
	m_alias.clear();
	m_aliasesOf.clear();
}

namespace
{
/** The grid key of cell (cx, cy). */
int64_t key(int64_t cx, int64_t cy)
{
	return int64_t((uint64_t(uint32_t(cx)) << 32) | uint64_t(uint32_t(cy)));
}
}  // namespace

int64_t CLandmarkFusion::cellOf(const Eigen::Vector2d& p) const
{
	return key(int64_t(std::floor(p.x() / m_cell)), int64_t(std::floor(p.y() / m_cell)));
}

void CLandmarkFusion::unregister(int32_t id, int64_t cell)
{
	const auto it = m_grid.find(cell);
	if (it == m_grid.end()) return;
	auto& v = it->second;
	v.erase(std::remove(v.begin(), v.end(), id), v.end());
	if (v.empty()) m_grid.erase(it);  // the grid holds only occupied cells
}

void CLandmarkFusion::noteRead(int32_t id, int step, const Eigen::Vector2d& p)
{
	const int64_t cell = cellOf(p);
	const auto [it, fresh] = m_tracks.try_emplace(id);
	TTrack& t = it->second;
	if (fresh)
		t.first = step;
	else if (t.cell == cell)
	{
		t.last = std::max(t.last, step);
		return;
	}
	else
		unregister(id, t.cell);
	t.last = std::max(t.last, step);
	t.cell = cell;
	m_grid[cell].push_back(id);
}

void CLandmarkFusion::forget(int32_t id)
{
	const auto it = m_tracks.find(id);
	if (it != m_tracks.end())
	{
		unregister(id, it->second.cell);
		m_tracks.erase(it);
	}
	const auto a = m_aliasesOf.find(id);
	if (a == m_aliasesOf.end()) return;
	for (const int32_t g : a->second) m_alias.erase(g);
	m_aliasesOf.erase(a);
}

std::vector<std::pair<int32_t, double>> CLandmarkFusion::compatible(
    int32_t id, const std::function<double(int32_t, int32_t)>& d2) const
{
	std::vector<std::pair<int32_t, double>> out;
	const auto self = m_tracks.find(id);
	if (self == m_tracks.end()) return out;
	const TTrack& t = self->second;
	const int64_t cx = int32_t(uint32_t(uint64_t(t.cell) >> 32)), cy = int32_t(uint32_t(t.cell));
	for (int64_t dx = -1; dx <= 1; ++dx)
		for (int64_t dy = -1; dy <= 1; ++dy)
		{
			const auto cell = m_grid.find(key(cx + dx, cy + dy));
			if (cell == m_grid.end()) continue;
			for (const int32_t n : cell->second)
			{
				if (n == id) continue;
				const TTrack& o = m_tracks.at(n);
				if (!(o.last < t.first || t.last < o.first)) continue;  // read in a common step
				const double v = d2(id, n);
				if (v <= m_threshold) out.emplace_back(n, v);
			}
		}
	return out;
}

std::vector<TFusionPair> CLandmarkFusion::decide(
    const std::vector<int32_t>& read, const std::function<double(int32_t, int32_t)>& d2) const
{
	std::vector<TFusionPair> pairs;
	if (!enabled()) return pairs;
	for (const int32_t c : read)
	{
		const auto cc = compatible(c, d2);
		if (cc.size() != 1) continue;
		const int32_t n = cc.front().first;
		const auto nc = compatible(n, d2);
		if (nc.size() != 1 || nc.front().first != c) continue;
		const TTrack &tc = m_tracks.at(c), &tn = m_tracks.at(n);
		const bool cOlder = tc.first < tn.first || (tc.first == tn.first && c < n);
		TFusionPair f{cOlder ? c : n, cOlder ? n : c, cc.front().second};
		const bool listed =
		    std::any_of(pairs.begin(), pairs.end(),
		                [&](const TFusionPair& q) { return q.keep == f.keep && q.gone == f.gone; });
		if (!listed) pairs.push_back(f);
	}
	return pairs;
}

void CLandmarkFusion::fused(int32_t keep, int32_t gone, const Eigen::Vector2d& p)
{
	const auto g = m_tracks.find(gone);
	if (g == m_tracks.end() || !m_tracks.count(keep))
		throw std::logic_error("CLandmarkFusion::fused: landmark " + std::to_string(keep) + " or " +
		                       std::to_string(gone) + " is not registered");
	const TTrack tg = g->second;
	unregister(gone, tg.cell);
	m_tracks.erase(g);
	TTrack& tk = m_tracks.at(keep);
	tk.first = std::min(tk.first, tg.first);
	noteRead(keep, tg.last, p);  // the interval spans both; keep moves to p's cell
	// The IDs read as `gone` are read as `keep` from now on.
	std::vector<int32_t>& mine = m_aliasesOf[keep];
	const auto a = m_aliasesOf.find(gone);
	if (a != m_aliasesOf.end())
	{
		for (const int32_t id : a->second)
		{
			m_alias[id] = keep;
			mine.push_back(id);
		}
		m_aliasesOf.erase(a);
	}
	m_alias[gone] = keep;
	mine.push_back(gone);
}
}  // namespace dynslam::estimator
