/** @file odometry_autocorr.cpp
 * The correlation part of noise_estimation.h: integrated autocorrelation time of the
 * normalized odometry errors (the inflation of odometry.h's `inflated` model) and the NEES of
 * sums of consecutive increment errors. */
#include <dynslam/mrclam/noise_estimation.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynslam::mrclam
{
TAutocorrelation integratedAutocorrelation(const std::vector<std::vector<double>>& series, double c,
                                           int maxLag)
{
	if (!(c > 0)) throw std::invalid_argument("integratedAutocorrelation: c must be > 0");
	if (maxLag < 1) throw std::invalid_argument("integratedAutocorrelation: maxLag must be >= 1");
	TAutocorrelation a;
	double c0 = 0;
	for (const auto& z : series)
		for (double v : z)
		{
			c0 += v * v;
			a.n++;
		}
	a.rho.push_back(1.0);
	if (a.n == 0 || !(c0 > 0)) return a;
	c0 /= a.n;
	double tau = 1;
	for (int l = 1; l <= maxLag; l++)
	{
		double sum = 0;
		size_t nl = 0;
		for (const auto& z : series)
			for (size_t k = 0; k + l < z.size(); k++)
			{
				sum += z[k] * z[k + l];
				nl++;
			}
		if (nl == 0) break;
		const double rho = sum / nl / c0;
		a.rho.push_back(rho);
		tau += 2 * rho;
		a.window = l;
		if (l >= c * tau)
		{
			a.converged = true;
			break;
		}
	}
	a.tau = tau;
	return a;
}

namespace
{
/** Mean over non-overlapping windows of W consecutive samples (per series) of
 * (sum e)^2 / (sum var). */
double windowNees(const std::vector<std::vector<double>>& e,
                  const std::vector<std::vector<double>>& var, int W)
{
	double sum = 0;
	size_t n = 0;
	for (size_t s = 0; s < e.size(); s++)
		for (size_t k = 0; k + W <= e[s].size(); k += W)
		{
			double se = 0, sv = 0;
			for (int i = 0; i < W; i++)
			{
				se += e[s][k + i];
				sv += var[s][k + i];
			}
			if (sv > 0)
			{
				sum += se * se / sv;
				n++;
			}
		}
	return n ? sum / n : 0;
}
}  // namespace

void estimateOdometryCorrelation(const TNoiseSamples& s, double trimChi2, TNoiseEstimate& est)
{
	TOdometryNoiseModel white = est.odometry;
	white.model = TOdometryNoiseModel::Model::white;
	const double clip = std::sqrt(trimChi2);
	// per robot (contiguous runs of the same ego): errors, variances, normalized errors
	std::vector<std::vector<double>> ex, vx, zx, ephi, vphi, zphi;
	int ego = -1;
	for (const auto& o : s.odo)
	{
		if (o.ego != ego || ex.empty())
		{
			ego = o.ego;
			for (auto* v : {&ex, &vx, &zx, &ephi, &vphi, &zphi}) v->emplace_back();
			// y gets its own series (x and y are pooled as separate series)
			for (auto* v : {&ex, &vx, &zx}) v->emplace_back();
		}
		TOdometryIncrement inc;
		inc.distance = o.distance;
		inc.angle = o.angle;
		const Eigen::Matrix3d C = white.covariance(inc);
		const size_t ix = ex.size() - 2, iy = ex.size() - 1;
		const Eigen::Vector3d sd = C.diagonal().cwiseMax(1e-30).cwiseSqrt();
		auto push = [&](size_t i, double e, double sdev, auto& E, auto& V, auto& Z)
		{
			E[i].push_back(e);
			V[i].push_back(sdev * sdev);
			Z[i].push_back(std::clamp(e / sdev, -clip, clip));
		};
		push(ix, o.e.x(), sd.x(), ex, vx, zx);
		push(iy, o.e.y(), sd.y(), ex, vx, zx);
		push(ephi.size() - 1, o.e.z(), sd.z(), ephi, vphi, zphi);
	}
	est.odo_acf_xy = integratedAutocorrelation(zx);
	est.odo_acf_phi = integratedAutocorrelation(zphi);
	est.odometry.tau_xy = std::max(1.0, est.odo_acf_xy.tau);
	est.odometry.tau_phi = std::max(1.0, est.odo_acf_phi.tau);
	est.odo_window_nees_xy.clear();
	est.odo_window_nees_phi.clear();
	for (int W : est.odo_window_lengths)
	{
		est.odo_window_nees_xy.push_back(windowNees(ex, vx, W));
		est.odo_window_nees_phi.push_back(windowNees(ephi, vphi, W));
	}
}
}  // namespace dynslam::mrclam
