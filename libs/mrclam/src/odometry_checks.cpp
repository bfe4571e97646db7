/** @file odometry_checks.cpp
 * The odometry parts of noise_estimation.h that re-integrate or compose an import: the delay
 * scores and the dead-reckoning report. */
#include <dynslam/mrclam/noise_estimation.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace dynslam::mrclam
{
double TDelayScore::rmsPhi() const { return n ? std::sqrt(sse_phi / n) : 0; }
double TDelayScore::rmsXY() const { return n ? std::sqrt(sse_xy / n) : 0; }

std::vector<TDelayScore> scoreOdometryDelays(const TDataset& d, const TImportResult& res,
                                             const std::vector<double>& delays, double scaleV,
                                             double scaleW)
{
	const CTrajectoryInterpolator ego(d.groundTruth.at(d.ego));
	std::vector<Eigen::Vector3d> gtInc;
	for (size_t k = 1; k < res.steps.size(); k++)
		gtInc.push_back(relativeSE2(ego.at(res.steps[k - 1].t), ego.at(res.steps[k].t)));
	std::vector<TDelayScore> out;
	for (double dl : delays)
	{
		const COdometryIntegrator odo(d.odometry, dl, scaleV, scaleW);
		TDelayScore s;
		s.delay = dl;
		for (size_t k = 1; k < res.steps.size(); k++)
		{
			const Eigen::Vector3d inc = odo.integrate(res.steps[k - 1].t, res.steps[k].t).delta;
			const double ephi = wrapAngle(gtInc[k - 1].z() - inc.z());
			s.sse_phi += ephi * ephi;
			s.sse_xy += (gtInc[k - 1].head<2>() - inc.head<2>()).squaredNorm();
			s.n++;
		}
		out.push_back(s);
	}
	return out;
}

void poolDelayScores(std::vector<TDelayScore>& a, const std::vector<TDelayScore>& b)
{
	if (a.empty())
	{
		a = b;
		return;
	}
	if (a.size() != b.size()) throw std::invalid_argument("poolDelayScores: sizes differ");
	for (size_t i = 0; i < a.size(); i++)
	{
		a[i].n += b[i].n;
		a[i].sse_phi += b[i].sse_phi;
		a[i].sse_xy += b[i].sse_xy;
	}
}

TDelayScore bestDelay(const std::vector<TDelayScore>& scores)
{
	if (scores.empty()) throw std::invalid_argument("bestDelay: no scores");
	return *std::min_element(scores.begin(), scores.end(),
	                         [](const auto& a, const auto& b) { return a.rmsPhi() < b.rmsPhi(); });
}

std::string delayScoresText(const std::vector<TDelayScore>& scores)
{
	std::ostringstream o;
	o << std::setprecision(4);
	o << "  odometry delay [s]: RMS heading error per step [deg] / RMS position error per step "
	     "[mm]\n";
	for (const auto& s : scores)
		o << "    " << std::setw(5) << s.delay << ": " << std::setw(7) << s.rmsPhi() * 180 / M_PI
		  << " / " << std::setw(7) << s.rmsXY() * 1000 << "\n";
	const auto b = bestDelay(scores);
	o << "  best delay: " << b.delay << " s\n";
	return o.str();
}

std::vector<TDeadReckoningPoint> deadReckoning(const TImportResult& res,
                                               const std::vector<double>& times)
{
	std::vector<TDeadReckoningPoint> out(times.size());
	for (size_t i = 0; i < times.size(); i++) out[i].T = times[i];
	const auto& gt = res.gt;
	if (res.steps.empty() || gt.numSteps() != res.steps.size()) return out;
	Eigen::Vector3d x = gt.ego[0];
	Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
	double path = 0;
	for (size_t k = 0; k < res.steps.size(); k++)
	{
		if (k > 0)
		{
			const Eigen::Vector3d& u = res.steps[k].increment.delta;
			const double c = std::cos(x.z()), s = std::sin(x.z());
			Eigen::Matrix3d F = Eigen::Matrix3d::Identity(), G = Eigen::Matrix3d::Identity();
			F(0, 2) = -s * u.x() - c * u.y();
			F(1, 2) = c * u.x() - s * u.y();
			G.topLeftCorner<2, 2>() << c, -s, s, c;
			P = F * P * F.transpose() + G * res.steps[k].cov * G.transpose();
			x = composeSE2(x, u);
			path += (gt.ego[k].head<2>() - gt.ego[k - 1].head<2>()).norm();
		}
		const double t = res.steps[k].t - res.steps[0].t;
		for (auto& p : out)
			if (t <= p.T)
			{
				p.error = (x.head<2>() - gt.ego[k].head<2>()).norm();
				p.heading_error = wrapAngle(x.z() - gt.ego[k].z());
				p.sigma = std::sqrt(P(0, 0) + P(1, 1));
				p.path = path;
			}
	}
	return out;
}

std::string deadReckoningText(const std::vector<TDeadReckoningPoint>& pts)
{
	std::ostringstream o;
	o << std::setprecision(3);
	o << "  dead reckoning (T [s]: position error [m] / model sigma [m] / path [m] / error per "
	     "path / heading error [deg]):\n";
	for (const auto& p : pts)
		o << "    " << p.T << ": " << p.error << " / " << p.sigma << " / " << p.path << " / "
		  << (p.path > 0 ? 100 * p.error / p.path : 0) << "% / " << p.heading_error * 180 / M_PI
		  << "\n";
	return o.str();
}
}  // namespace dynslam::mrclam
