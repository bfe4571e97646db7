/** CClassifyingRouter: the tests of a static track (classify_static_test) and of a moving one
 * that stops (doc/results/classification.md). */
#include <dynslam/estimator/classifying_router.h>

#include <Eigen/LU>
#include <cmath>

namespace dynslam::estimator
{
bool CClassifyingRouter::mapInnovation(int32_t id, TStaticInnovation& inn) const
{
	if (m_p.static_test != TClassifyParams::StaticTest::Map || !m_ctx->static_innovation)
		return false;
	const auto it = m_rawNow.find(id);
	return it != m_rawNow.end() && m_ctx->static_innovation(id, it->second, inn);
}

bool CClassifyingRouter::checkStatic(int32_t id, TTrack& t, const TPoint2& z, int step)
{
	TStaticInnovation inn;
	std::optional<double> nis;
	if (mapInnovation(id, inn))
		nis = inn.nu.dot(inn.S.inverse() * inn.nu);
	else if (t.q_valid)
	{
		const Eigen::Vector2d nu = z.p - t.q.p;
		const Eigen::Matrix2d S = t.q.C + z.C;
		nis = nu.dot(S.inverse() * nu);
	}
	if (nis && m_p.reclassify_count > 0 && *nis > chiSquareQuantile(m_p.reclassify_gate, 2))
	{
		++t.bad_streak;
		return false;
	}
	t.bad_streak = 0;
	t.last_good = step;
	if (!t.q_valid)
	{
		t.q = z;
		t.q_valid = true;
		return true;
	}
	const Eigen::Vector2d nu = z.p - t.q.p;
	const Eigen::Matrix2d S = t.q.C + z.C;
	const Eigen::Matrix2d K = t.q.C * S.inverse();
	t.q.p += K * nu;
	t.q.C = (Eigen::Matrix2d::Identity() - K) * t.q.C;
	t.q.C = 0.5 * (t.q.C + t.q.C.transpose());
	return true;
}

void CClassifyingRouter::reclassifyStatic(int32_t id, TTrack& t, TRoutedStep& out,
                                          std::vector<int32_t>& turnedMoving,
                                          const std::function<bool(int32_t)>& isKnownStatic) const
{
	turnedMoving.push_back(id);
	if (isKnownStatic(id) && m_p.surgery)
		t.converting = true;  // its landmark becomes an f_0 (registerConverted)
	else if (isKnownStatic(id))
		out.reclassified.push_back(id);
}

bool CClassifyingRouter::stoppedEvidence(TTrack& t, const TPoint2& z)
{
	if (m_p.stop_count <= 0) return false;
	if (t.q_valid)
	{
		const Eigen::Vector2d nu = z.p - t.q.p;
		const Eigen::Matrix2d S = t.q.C + z.C;
		if (nu.dot(S.inverse() * nu) <= chiSquareQuantile(m_p.reclassify_gate, 2))
		{
			const Eigen::Matrix2d K = t.q.C * S.inverse();
			t.q.p += K * nu;
			t.q.C = (Eigen::Matrix2d::Identity() - K) * t.q.C;
			t.q.C = 0.5 * (t.q.C + t.q.C.transpose());
			return ++t.still_streak >= m_p.stop_count;
		}
	}
	t.q = z;  // (re)starts the static filter at this reading
	t.q_valid = true;
	t.still_streak = 0;
	return false;
}
}  // namespace dynslam::estimator
