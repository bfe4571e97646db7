#include <dynslam/core/models/assignment.h>
#include <dynslam/eval/estimates.h>  // kNaN
#include <dynslam/eval/mot_metrics.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>

namespace dynslam::eval
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

void checkOptions(const TMotOptions& o)
{
	if (!(o.max_distance >= 0 && std::isfinite(o.max_distance)))
		throw std::invalid_argument("MOT metrics: max_distance must be finite and >= 0");
	if (!(o.min_iou > 0 && o.min_iou <= 1))
		throw std::invalid_argument("MOT metrics: min_iou must be in (0, 1]");
	if (o.recall_levels < 1) throw std::invalid_argument("MOT metrics: recall_levels must be >= 1");
}

void checkUniqueIds(const std::vector<TMotObject>& v, size_t frame, const char* what)
{
	std::set<int> ids;
	for (const auto& b : v)
		if (!ids.insert(b.id).second)
			throw std::invalid_argument("MOT metrics: frame " + std::to_string(frame) + ": " +
			                            what + " ID " + std::to_string(b.id) + " given twice");
}

/** The pair's distance (centre distance, or 1 - IoU) if it matches, else +infinity; sim = the
 * MOTP value of the pair (distance or IoU). */
double pairCost(const TMotObject& t, const TMotObject& h, const TMotOptions& o, double* sim)
{
	if (t.cls != h.cls) return kInf;
	if (o.criterion == EMotCriterion::CentreDistance)
	{
		const double d = bevCentreDistance(t.box, h.box);
		if (sim) *sim = d;
		return d <= o.max_distance ? d : kInf;
	}
	const double iou = bevIoU(t.box, h.box);
	if (sim) *sim = iou;
	return iou >= o.min_iou ? 1 - iou : kInf;
}

struct TRun
{
	TMotCounts c;
	double sim_sum = 0;
	std::vector<double> matched_scores;
};

struct TTruthState
{
	int last_hyp = -1;     ///< the mapping M (-1: never matched)
	bool tracked = false;  ///< matched at its previous annotated frame
	bool ever = false;     ///< matched at some earlier frame
};

/** Steps 1-2 of CLEAR MOT in one frame: the matched pairs (truth index, hyp index). */
std::vector<std::pair<size_t, size_t>> matchFrame(const TMotFrame& f, const std::vector<char>& keep,
                                                  std::map<int, TTruthState>& state,
                                                  const TMotOptions& o)
{
	std::vector<std::pair<size_t, size_t>> pairs;
	std::vector<char> tUsed(f.truth.size(), 0), hUsed(f.hyp.size(), 0);
	for (size_t i = 0; i < f.truth.size(); ++i)  // 1. keep valid correspondences of M
	{
		const int last = state[f.truth[i].id].last_hyp;
		for (size_t j = 0; j < f.hyp.size() && last >= 0; ++j)
			if (keep[j] && !hUsed[j] && f.hyp[j].id == last &&
			    std::isfinite(pairCost(f.truth[i], f.hyp[j], o, nullptr)))
			{
				tUsed[i] = hUsed[j] = 1;
				pairs.emplace_back(i, j);
				break;
			}
	}
	std::vector<size_t> ti, hj;  // 2. Hungarian on the rest
	for (size_t i = 0; i < f.truth.size(); ++i)
		if (!tUsed[i]) ti.push_back(i);
	for (size_t j = 0; j < f.hyp.size(); ++j)
		if (keep[j] && !hUsed[j]) hj.push_back(j);
	Eigen::MatrixXd cost(long(ti.size()), long(hj.size()));
	for (size_t a = 0; a < ti.size(); ++a)
		for (size_t b = 0; b < hj.size(); ++b)
			cost(long(a), long(b)) = pairCost(f.truth[ti[a]], f.hyp[hj[b]], o, nullptr);
	const std::vector<int> col = models::solveAssignment(cost);
	for (size_t a = 0; a < ti.size(); ++a)
		if (col[a] >= 0) pairs.emplace_back(ti[a], hj[size_t(col[a])]);
	return pairs;
}

TRun run(const std::vector<TMotFrame>& frames, const TMotOptions& o, double minScore)
{
	TRun r;
	std::map<int, TTruthState> state;
	for (size_t k = 0; k < frames.size(); ++k)
	{
		const TMotFrame& f = frames[k];
		checkUniqueIds(f.truth, k, "truth");
		checkUniqueIds(f.hyp, k, "hypothesis");
		std::vector<char> keep(f.hyp.size());
		size_t kept = 0;
		for (size_t j = 0; j < f.hyp.size(); ++j) kept += (keep[j] = f.hyp[j].score >= minScore);
		const auto pairs = matchFrame(f, keep, state, o);
		std::vector<char> tMatched(f.truth.size(), 0);
		for (const auto& [i, j] : pairs)
		{
			TTruthState& s = state[f.truth[i].id];
			if (s.last_hyp >= 0 && s.last_hyp != f.hyp[j].id) ++r.c.ids;
			s.last_hyp = f.hyp[j].id;
			tMatched[i] = 1;
			double sim = 0;
			pairCost(f.truth[i], f.hyp[j], o, &sim);
			r.sim_sum += sim;
			r.matched_scores.push_back(f.hyp[j].score);
		}
		for (size_t i = 0; i < f.truth.size(); ++i)
		{
			TTruthState& s = state[f.truth[i].id];
			// resumed after an interruption: matched now, not at its previous annotated frame,
			// and matched at some frame before
			if (tMatched[i] && !s.tracked && s.ever) ++r.c.frag;
			s.tracked = tMatched[i];
			s.ever = s.ever || tMatched[i];
		}
		r.c.frames++;
		r.c.gt += f.truth.size();
		r.c.hyp += kept;
		r.c.tp += pairs.size();
		r.c.fn += f.truth.size() - pairs.size();
		r.c.fp += kept - pairs.size();
	}
	if (r.c.gt > 0) r.c.mota = 1 - double(r.c.fn + r.c.fp + r.c.ids) / double(r.c.gt);
	if (r.c.tp > 0) r.c.motp = r.sim_sum / double(r.c.tp);
	return r;
}
}  // namespace

TMotCounts clearMot(const std::vector<TMotFrame>& frames, const TMotOptions& opts)
{
	checkOptions(opts);
	return run(frames, opts, -kInf).c;
}

TSamota samota(const std::vector<TMotFrame>& frames, const TMotOptions& opts)
{
	checkOptions(opts);
	TRun all = run(frames, opts, -kInf);
	TSamota s;
	const size_t gt = all.c.gt;
	if (gt == 0) return s;
	std::vector<double> sc = all.matched_scores;
	std::sort(sc.begin(), sc.end(), std::greater<double>());
	const int L = opts.recall_levels;
	double sum = 0;
	for (int l = 1; l <= L; ++l)
	{
		const double r = double(l) / L;
		const auto need = size_t(std::ceil(r * double(gt) - 1e-9));
		double thr = kNaN, sm = 0;
		if (need >= 1 && need <= sc.size())
		{
			thr = sc[need - 1];
			const TMotCounts c = run(frames, opts, thr).c;
			const double g = double(gt);
			sm = std::max(0.0, 1 - (double(c.ids + c.fp + c.fn) - (1 - r) * g) / (r * g));
		}
		s.recall.push_back(r);
		s.threshold.push_back(thr);
		s.smota.push_back(sm);
		sum += sm;
	}
	s.samota = sum / L;
	return s;
}

std::vector<TMotFrame> selectClass(const std::vector<TMotFrame>& frames, const std::string& cls)
{
	std::vector<TMotFrame> out(frames.size());
	for (size_t k = 0; k < frames.size(); ++k)
	{
		for (const auto& b : frames[k].truth)
			if (b.cls == cls) out[k].truth.push_back(b);
		for (const auto& b : frames[k].hyp)
			if (b.cls == cls) out[k].hyp.push_back(b);
	}
	return out;
}
}  // namespace dynslam::eval
