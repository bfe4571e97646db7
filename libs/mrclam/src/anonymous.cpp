/** Anonymous IDs and the class ground truth of an MRCLAM import (anonymous.h). */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/mrclam/anonymous.h>

#include <numeric>
#include <random>
#include <stdexcept>

namespace dynslam::mrclam
{
std::map<int, int32_t> anonymousSubjectIds(uint32_t seed)
{
	std::vector<int32_t> perm(kLastLandmark);
	std::iota(perm.begin(), perm.end(), 0);
	std::mt19937 rng(seed);
	for (size_t i = perm.size() - 1; i > 0; --i) std::swap(perm[i], perm[rng() % (i + 1)]);
	std::map<int, int32_t> m;
	for (int s = kFirstRobot; s <= kLastLandmark; ++s) m[s] = perm[size_t(s - kFirstRobot)];
	return m;
}

int32_t labelledSubjectId(int subject)
{
	if (isLandmarkSubject(subject)) return subject;
	if (isRobotSubject(subject)) return ids::objectFeatureId(subject, 0);
	throw std::invalid_argument("labelledSubjectId: no MRCLAM subject " + std::to_string(subject));
}

void makeAnonymous(TImportResult& res, uint32_t seed)
{
	if (!res.summary.anonymous_ids.empty())
		throw std::logic_error("makeAnonymous: the import is already anonymous");
	const std::map<int, int32_t> m = anonymousSubjectIds(seed);
	for (TStep& s : res.steps)
		for (TStepMeasurement& z : s.meas) z.id = m.at(z.subject);
	// The map truth under the IDs the filters see (so the landmark RMSE is scored).
	std::map<int32_t, Eigen::Vector2d> lm;
	for (const auto& [s, p] : res.gt.landmarks) lm[m.at(s)] = p;
	res.gt.landmarks = lm;
	res.summary.anonymous_ids = m;
	res.summary.anonymous_seed = seed;
}

std::vector<io::TReadingClass> classGroundTruth(const TImportResult& res)
{
	std::vector<io::TReadingClass> rows;
	for (size_t k = 0; k < res.steps.size(); ++k)
	{
		const TStep& s = res.steps[k];
		for (size_t i = 0; i < s.meas.size(); ++i)
		{
			const TStepMeasurement& z = s.meas[i];
			io::TReadingClass r;
			r.step = int(k);
			r.t = s.t;
			r.index = int(i);
			r.id = z.id;
			r.true_id = labelledSubjectId(z.subject);
			r.cls = isRobotSubject(z.subject) ? io::TrueClass::Moving : io::TrueClass::Static;
			r.object = isRobotSubject(z.subject) ? z.subject : -1;
			r.feature = isRobotSubject(z.subject) ? 0 : z.subject;
			rows.push_back(r);
		}
	}
	return rows;
}
}  // namespace dynslam::mrclam
