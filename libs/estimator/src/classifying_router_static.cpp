/** CClassifyingRouter: the tests of a static track (classify_static_test, the drift test
 * classify_drift_window) and of a moving one that stops (doc/classification.md). */
#include <dynslam/estimator/classifying_router.h>
#include <dynslam/models/se2.h>

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

bool CClassifyingRouter::checkStatic(int32_t id, TTrack& t, const TPoint2& z, int step,
                                     bool& drifted)
{
	TStaticInnovation inn;
	std::optional<double> nis;
	std::optional<TDriftTerm> term;  // the innovation in a frame fixed over the window
	const bool fromMap = mapInnovation(id, inn);
	if (fromMap)
	{
		nis = inn.nu.dot(inn.S.inverse() * inn.nu);
		// World frame: the landmark displacement that explains nu to first order.
		if (m_p.drift_window > 0 && std::abs(inn.J_z_f.determinant()) > 1e-12)
		{
			const Eigen::Matrix2d Ji = inn.J_z_f.inverse();
			term = TDriftTerm{Ji * inn.nu, Ji * inn.S * Ji.transpose()};
		}
	}
	else if (t.q_valid)
	{
		const Eigen::Vector2d nu = z.p - t.q.p;
		const Eigen::Matrix2d S = t.q.C + z.C;
		nis = nu.dot(S.inverse() * nu);
		if (m_p.drift_window > 0)
		{
			// The odometry frame: the robot frame rotated by the summed odometry headings.
			const Eigen::Matrix2d R = models::rot2(m_heading);
			term = TDriftTerm{R * nu, R * S * R.transpose()};
		}
	}
	if (nis && m_p.reclassify_count > 0 && *nis > chiSquareQuantile(m_p.reclassify_gate, 2))
	{
		++t.bad_streak;
		return false;
	}
	t.bad_streak = 0;
	t.last_good = step;
	if (term)
		drifted = driftDetected(t, *term, fromMap);
	else
		t.drift.clear();  // a restarted filter: the window restarts too
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

bool CClassifyingRouter::driftDetected(TTrack& t, const TDriftTerm& term, bool fromMap)
{
	const size_t n = size_t(m_p.drift_window);
	if (!t.drift.empty() && t.drift_map != fromMap) t.drift.clear();  // another frame
	if (t.drift.empty()) t.drift_next = 0;
	t.drift_map = fromMap;
	if (t.drift.size() < n)
		t.drift.push_back(term);
	else
		t.drift[t.drift_next] = term;
	t.drift_next = (t.drift_next + 1) % n;
	if (t.drift.size() < n) return false;
	const double T = driftStatistic(t.drift), q = chiSquareQuantile(m_p.drift_prob, 2);
	if (!m_p.drift_population) return T > q;
	// Population scale: the variance inflation of the window sum, the winsorised mean of T / 2
	// over every full window tested so far (all tracks); no decision before kDriftCalibration
	// tests. Never below 1 (the nominal test).
	m_driftSum += std::min(T, q);
	++m_driftTests;
	if (m_driftTests < kDriftCalibration) return false;
	return T > std::max(1.0, m_driftSum / m_driftTests / 2) * q;
}

void CClassifyingRouter::reclassifyStatic(int32_t id, TTrack& t, TRoutedStep& out,
                                          std::vector<int32_t>& turnedMoving,
                                          const std::function<bool(int32_t)>& isKnownStatic) const
{
	turnedMoving.push_back(id);
	t.drift.clear();
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
