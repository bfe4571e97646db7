/** @file class_metrics.cpp
 * Classification and grouping metrics (issue 12; class_metrics.h, doc/metrics.md). */
#include <dynslam/eval/class_metrics.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <utility>

namespace dynslam::eval
{
namespace
{
void checkSizes(size_t a, size_t b, const char* what)
{
	if (a != b)
		throw std::invalid_argument(std::string(what) + ": " + std::to_string(a) +
		                            " ground-truth rows but " + std::to_string(b) + " decisions");
}

void count(TBinaryScores& s, bool truthMoving, Decision d)
{
	const bool predMoving = d == Decision::Moving;
	if (d == Decision::Undecided) ++s.undecided;
	if (truthMoving && predMoving) ++s.tp;
	if (!truthMoving && predMoving) ++s.fp;
	if (truthMoving && !predMoving) ++s.fn;
	if (!truthMoving && !predMoving) ++s.tn;
}

double ratio(double num, double den) { return den > 0 ? num / den : kNaN; }

/** Row indices sorted by (step, index). */
std::vector<size_t> chronological(const std::vector<io::TReadingClass>& t)
{
	std::vector<size_t> o(t.size());
	std::iota(o.begin(), o.end(), 0);
	std::stable_sort(o.begin(), o.end(),
	                 [&](size_t a, size_t b) {
		                 return std::pair(t[a].step, t[a].index) < std::pair(t[b].step, t[b].index);
	                 });
	return o;
}

double choose2(double n) { return 0.5 * n * (n - 1); }
}  // namespace

TBinaryScores finishScores(TBinaryScores s)
{
	s.precision = ratio(double(s.tp), double(s.tp + s.fp));
	s.recall = ratio(double(s.tp), double(s.tp + s.fn));
	s.f1 = ratio(2.0 * double(s.tp), double(2 * s.tp + s.fp + s.fn));
	return s;
}

TBinaryScores perReadingScores(const std::vector<io::TReadingClass>& truth,
                               const std::vector<Decision>& decisions)
{
	checkSizes(truth.size(), decisions.size(), "perReadingScores");
	TBinaryScores s;
	for (size_t i = 0; i < truth.size(); ++i)
		count(s, truth[i].cls == io::TrueClass::Moving, decisions[i]);
	return finishScores(s);
}

TBinaryScores perTrackScores(const std::vector<io::TReadingClass>& truth,
                             const std::vector<Decision>& decisions)
{
	checkSizes(truth.size(), decisions.size(), "perTrackScores");
	std::map<int32_t, size_t> last;  // track ID -> row of its last reading
	for (size_t i : chronological(truth))
		if (truth[i].id >= 0) last[truth[i].id] = i;
	TBinaryScores s;
	for (const auto& [id, i] : last) count(s, truth[i].cls == io::TrueClass::Moving, decisions[i]);
	return finishScores(s);
}

TDelaySummary detectionDelays(const std::vector<io::TReadingClass>& truth,
                              const std::vector<Decision>& decisions, bool includeFirstSightings)
{
	checkSizes(truth.size(), decisions.size(), "detectionDelays");
	// Readings of each true object feature, in time order.
	std::map<std::pair<int32_t, int32_t>, std::vector<size_t>> byFeature;
	for (size_t i : chronological(truth))
		if (truth[i].object >= 0) byFeature[{truth[i].object, truth[i].feature}].push_back(i);
	TDelaySummary out;
	double sum = 0;
	for (const auto& [key, rows] : byFeature)
		for (size_t r = 0; r < rows.size(); ++r)
		{
			const bool moving = truth[rows[r]].cls == io::TrueClass::Moving;
			const bool prevStatic = r > 0 && truth[rows[r - 1]].cls == io::TrueClass::Static;
			if (!moving || !(prevStatic || (r == 0 && includeFirstSightings))) continue;
			TOnsetDelay d;
			d.object = key.first;
			d.feature = key.second;
			d.onset_step = truth[rows[r]].step;
			for (size_t q = r; q < rows.size() && truth[rows[q]].cls == io::TrueClass::Moving; ++q)
				if (decisions[rows[q]] == Decision::Moving)
				{
					d.detect_step = truth[rows[q]].step;
					d.delay = d.detect_step - d.onset_step;
					break;
				}
			if (d.delay >= 0)
			{
				++out.detected;
				sum += d.delay;
				out.max_delay = std::max(out.max_delay, d.delay);
			}
			else
				++out.missed;
			out.onsets.push_back(d);
		}
	if (out.detected > 0) out.mean_delay = sum / double(out.detected);
	return out;
}

double adjustedRandIndex(const std::vector<int64_t>& truth, const std::vector<int64_t>& estimate)
{
	if (truth.size() != estimate.size())
		throw std::invalid_argument("adjustedRandIndex: " + std::to_string(truth.size()) +
		                            " true labels but " + std::to_string(estimate.size()) +
		                            " estimated labels");
	if (truth.empty()) throw std::invalid_argument("adjustedRandIndex: no items");
	std::map<std::pair<int64_t, int64_t>, double> nij;
	std::map<int64_t, double> a, b;
	for (size_t i = 0; i < truth.size(); ++i)
	{
		nij[{truth[i], estimate[i]}] += 1;
		a[truth[i]] += 1;
		b[estimate[i]] += 1;
	}
	double index = 0, sa = 0, sb = 0;
	for (const auto& [k, n] : nij) index += choose2(n);
	for (const auto& [k, n] : a) sa += choose2(n);
	for (const auto& [k, n] : b) sb += choose2(n);
	const double expected = sa * sb / choose2(double(truth.size()));
	const double den = 0.5 * (sa + sb) - expected;
	// den = 0 only for identical partitions (n = 1, one cluster each, singletons each).
	if (den == 0 || truth.size() == 1) return 1.0;
	return (index - expected) / den;
}

double groupingAri(const std::vector<io::TReadingClass>& truth,
                   const std::vector<int64_t>& estimatedGroup)
{
	if (truth.size() != estimatedGroup.size())
		throw std::invalid_argument("groupingAri: " + std::to_string(truth.size()) +
		                            " ground-truth rows but " +
		                            std::to_string(estimatedGroup.size()) + " groups");
	std::vector<int64_t> t, e;
	int64_t singleton = -1;  // ungrouped readings: distinct negative labels
	for (size_t i = 0; i < truth.size(); ++i)
	{
		if (truth[i].cls != io::TrueClass::Moving) continue;
		t.push_back(truth[i].object);
		e.push_back(estimatedGroup[i] >= 0 ? estimatedGroup[i] : singleton--);
	}
	return t.empty() ? kNaN : adjustedRandIndex(t, e);
}

TIdentityCounts identityCounts(const std::vector<io::TReadingClass>& truth,
                               const std::vector<int64_t>& estimatedGroup)
{
	if (truth.size() != estimatedGroup.size())
		throw std::invalid_argument("identityCounts: " + std::to_string(truth.size()) +
		                            " ground-truth rows but " +
		                            std::to_string(estimatedGroup.size()) + " groups");
	std::map<int64_t, std::set<int32_t>> objectsOf;  // identity -> true objects
	std::map<int32_t, std::set<int64_t>> groupsOf;   // true object -> identities
	for (size_t i = 0; i < truth.size(); ++i)
	{
		if (truth[i].cls != io::TrueClass::Moving) continue;
		std::set<int64_t>& g = groupsOf[truth[i].object];
		if (estimatedGroup[i] < 0) continue;
		g.insert(estimatedGroup[i]);
		objectsOf[estimatedGroup[i]].insert(truth[i].object);
	}
	TIdentityCounts c;
	c.true_objects = groupsOf.size();
	c.identities = objectsOf.size();
	for (const auto& [g, objects] : objectsOf) c.impure += objects.size() > 1 ? 1 : 0;
	for (const auto& [o, groups] : groupsOf) c.split += groups.size() > 1 ? 1 : 0;
	return c;
}

TWrongStatic wrongStaticLandmarks(const std::vector<io::TReadingClass>& truth,
                                  const std::vector<int32_t>& mapIds)
{
	std::map<int32_t, bool> bad;  // written ID -> has a moving or clutter reading
	for (const io::TReadingClass& r : truth)
		if (r.id >= 0) bad[r.id] = bad[r.id] || r.cls != io::TrueClass::Static;
	TWrongStatic w;
	w.map_size = mapIds.size();
	for (int32_t id : mapIds)
	{
		const auto it = bad.find(id);
		if (it == bad.end())
			++w.unknown;
		else if (it->second)
		{
			++w.wrong;
			w.wrong_ids.push_back(id);
		}
	}
	return w;
}
}  // namespace dynslam::eval
