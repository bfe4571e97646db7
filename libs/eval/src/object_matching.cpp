#include <dynslam/core/models/se2.h>
#include <dynslam/eval/object_matching.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

namespace dynslam::eval
{
namespace
{
/** The candidate (>= 0) with the most readings, ties to the smaller; -1 ("none") wins only
 * with strictly more readings than that candidate. */
int32_t majority(const std::map<int32_t, size_t>& counts)
{
	int32_t best = -1;
	size_t bestN = 0;
	for (const auto& [c, n] : counts)  // ascending: a tie keeps the smaller candidate
		if (c >= 0 && n > bestN)
		{
			best = c;
			bestN = n;
		}
	const auto none = counts.find(-1);
	return none != counts.end() && none->second > bestN ? -1 : best;
}
}  // namespace

std::map<int32_t, int32_t> matchObjectsByReadings(const std::vector<int32_t>& estObject,
                                                  const std::vector<io::TReadingClass>& truth)
{
	if (estObject.size() != truth.size())
		throw std::invalid_argument("matchObjectsByReadings: " + std::to_string(estObject.size()) +
		                            " estimated readings, " + std::to_string(truth.size()) +
		                            " in the class ground truth");
	std::map<int32_t, std::map<int32_t, size_t>> votes;  // estimated -> true -> readings
	for (size_t i = 0; i < estObject.size(); ++i)
		if (estObject[i] >= 0) ++votes[estObject[i]][truth[i].object < 0 ? -1 : truth[i].object];
	std::map<int32_t, int32_t> match;
	for (const auto& [est, counts] : votes) match[est] = majority(counts);
	return match;
}

TRunEstimates withMatchedObjects(const TRunEstimates& est, const std::map<int32_t, int32_t>& match)
{
	auto to = [&](int32_t o)
	{
		const auto it = match.find(o);
		return it == match.end() ? int32_t(-1) : it->second;
	};
	TRunEstimates out = est;
	for (auto& p : out.object_poses) p.object = to(p.object);
	for (auto& f : out.object_features) f.object = to(f.object);
	return out;
}

std::optional<TVelocityErrors> classifyingVelocityErrors(
    const io::TGroundTruth& gt, const TRunEstimates& est, const std::vector<int32_t>& estObject,
    const std::vector<io::TReadingClass>* truth)
{
	if (!truth) return std::nullopt;
	return objectVelocityErrors(gt,
	                            withMatchedObjects(est, matchObjectsByReadings(estObject, *truth)));
}

void blankObjectColumns(TRunMetrics& m)
{
	for (auto& o : m.objects)
	{
		const int32_t id = o.object;
		o = TObjectMetrics();
		o.object = id;
	}
}

namespace
{
/** What the readings say about one estimated object of a classifying run. */
struct TEstObject
{
	int32_t match = -1;                                ///< its true object (matchObjectsByReadings)
	size_t own = 0;                                    ///< its readings of that true object
	int first_step = std::numeric_limits<int>::max();  ///< its time 0
	std::map<int32_t, std::map<int32_t, size_t>> votes;  ///< feature -> true feature -> readings
	std::set<int32_t> founders;                          ///< its features read at first_step
	std::map<int32_t, int32_t> feature;                  ///< feature -> matched true feature
};

std::map<int32_t, TEstObject> describeObjects(const TReadingObjects& r,
                                              const std::vector<io::TReadingClass>& truth)
{
	if (r.object.size() != truth.size() || r.feature.size() != truth.size())
		throw std::invalid_argument("scoreClassifyingAgents: " + std::to_string(r.object.size()) +
		                            " objects and " + std::to_string(r.feature.size()) +
		                            " features of readings, " + std::to_string(truth.size()) +
		                            " in the class ground truth");
	const auto match = matchObjectsByReadings(r.object, truth);
	std::map<int32_t, TEstObject> out;
	for (size_t i = 0; i < truth.size(); ++i)
	{
		if (r.object[i] < 0) continue;
		TEstObject& e = out[r.object[i]];
		e.match = match.at(r.object[i]);
		const bool own = e.match >= 0 && truth[i].object == e.match && truth[i].feature >= 0;
		e.own += own;
		e.first_step = std::min(e.first_step, truth[i].step);
		if (r.feature[i] >= 0) ++e.votes[r.feature[i]][own ? truth[i].feature : -1];
	}
	for (size_t i = 0; i < truth.size(); ++i)
		if (r.object[i] >= 0 && r.feature[i] >= 0 && truth[i].step == out[r.object[i]].first_step)
			out[r.object[i]].founders.insert(r.feature[i]);
	for (auto& [o, e] : out)
		for (const auto& [j, v] : e.votes)
			if (const int32_t f = majority(v); f >= 0) e.feature[j] = f;
	return out;
}

/** Centroid of the given columns of a feature matrix. */
Eigen::Vector2d centroid(const Eigen::Matrix2Xd& f, const std::vector<int32_t>& cols)
{
	Eigen::Vector2d c = Eigen::Vector2d::Zero();
	for (const int32_t i : cols) c += f.col(i);
	return c / double(cols.size());
}

/** The f_0 of estimated object `o` against the truth at its time 0 s. */
void scoreAgentFeatures(TObjectMetrics& om, const io::TObjectGroundTruth& t, int32_t o,
                        const TEstObject& e, const TRunEstimates& est)
{
	std::vector<double> x, y;
	std::set<int32_t> scored;
	for (const auto& f : est.object_features)
	{
		if (f.object != o) continue;
		const auto it = e.feature.find(f.feature);
		if (it == e.feature.end() || it->second >= t.num_features) continue;
		const Eigen::Vector2d truth = t.features[size_t(e.first_step)].col(it->second);
		if (!truth.allFinite()) continue;
		x.push_back(f.mean[0] - truth[0]);
		y.push_back(f.mean[1] - truth[1]);
		scored.insert(it->second);
	}
	om.features = rmseOf(x, y, {});
	om.features_missing = size_t(t.num_features) - scored.size();
}

/** The poses of estimated object `o` against the truth's motion since its time 0 s. */
void scoreAgentPoses(TObjectMetrics& om, const io::TObjectGroundTruth& t, int32_t o,
                     const TEstObject& e, const TRunEstimates& est)
{
	const int s = e.first_step;
	std::vector<int32_t> all(size_t(t.num_features)), ref;
	for (int32_t i = 0; i < t.num_features; ++i) all[size_t(i)] = i;
	for (const int32_t j : e.founders)
		if (const auto it = e.feature.find(j); it != e.feature.end() && it->second < t.num_features)
			ref.push_back(it->second);
	const Eigen::Vector2d c0 = centroid(t.features[size_t(t.first_step)], all);
	const Eigen::Vector2d c = centroid(t.features[size_t(s)], ref.empty() ? all : ref);
	const Eigen::Vector3d& xs = t.pose[size_t(s)];
	std::vector<double> x, y, th;
	for (const auto& p : est.object_poses)
	{
		if (p.object != o) continue;
		if (p.step < s || p.step >= int(t.pose.size()) || !t.pose[size_t(p.step)].allFinite())
		{
			++om.poses_skipped;
			continue;
		}
		const Eigen::Vector3d& xk = t.pose[size_t(p.step)];
		const double dth = xk[2] - xs[2], co = std::cos(dth), si = std::sin(dth);
		const Eigen::Vector2d q = c - c0 - xs.head<2>();
		const Eigen::Vector2d g =
		    Eigen::Vector2d(co * q.x() - si * q.y(), si * q.x() + co * q.y()) + c0 +
		    xk.head<2>();  // G_k(c) = T_k(T_s^-1(c))
		x.push_back(p.mean[0] - (g.x() - c.x()));
		y.push_back(p.mean[1] - (g.y() - c.y()));
		if (p.mean.size() == 3) th.push_back(models::wrapToPi(p.mean[2] - models::wrapToPi(dth)));
	}
	om.poses = rmseOf(x, y, th);
}
}  // namespace

std::vector<TAgentMatch> scoreClassifyingAgents(TRunMetrics& m, const io::TGroundTruth& gt,
                                                const TRunEstimates& est,
                                                const TReadingObjects& reads,
                                                const std::vector<io::TReadingClass>& truth)
{
	const auto objects = describeObjects(reads, truth);
	std::vector<TAgentMatch> out;
	m.objects.clear();
	for (const auto& t : gt.objects)
	{
		TAgentMatch a;
		a.truth = t.object;
		for (const auto& [o, e] : objects)  // ascending: a tie keeps the smaller number
			if (e.match == t.object && e.match >= 0)
			{
				++a.candidates;
				if (a.estimated < 0 || e.own > a.readings)
				{
					a.estimated = o;
					a.readings = e.own;
				}
			}
		TObjectMetrics om;
		om.object = t.object;
		om.translation_only = t.translationOnly();
		const TEstObject* e = a.estimated >= 0 ? &objects.at(a.estimated) : nullptr;
		if (e && t.first_step >= 0 && e->first_step >= 0 && e->first_step < int(t.pose.size()) &&
		    t.pose[size_t(e->first_step)].allFinite())
		{
			a.first_step = e->first_step;
			a.features_matched = e->feature.size();
			scoreAgentFeatures(om, t, a.estimated, *e, est);
			scoreAgentPoses(om, t, a.estimated, *e, est);
		}
		m.objects.push_back(om);
		out.push_back(a);
	}
	return out;
}
}  // namespace dynslam::eval
