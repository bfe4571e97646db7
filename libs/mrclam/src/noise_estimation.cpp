#include <dynslam/mrclam/noise_estimation.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace dynslam::mrclam
{
namespace
{
double median(std::vector<double> v)
{
	if (v.empty()) return 0;
	const size_t n = v.size() / 2;
	std::nth_element(v.begin(), v.begin() + n, v.end());
	double m = v[n];
	if (v.size() % 2 == 0)
	{
		std::nth_element(v.begin(), v.begin() + n - 1, v.end());
		m = 0.5 * (m + v[n - 1]);
	}
	return m;
}

void meanStd(const std::vector<double>& v, double& mean, double& std)
{
	mean = std = 0;
	if (v.empty()) return;
	for (double x : v) mean += x;
	mean /= v.size();
	for (double x : v) std += (x - mean) * (x - mean);
	std = v.size() > 1 ? std::sqrt(std / (v.size() - 1)) : 0;
}

/** Weighted non-negative least squares y ~ A c by enumerating the active sets (3 columns). */
Eigen::Vector3d nnls3(const Eigen::MatrixX3d& A, const Eigen::VectorXd& y, const Eigen::VectorXd& w)
{
	Eigen::Vector3d best = Eigen::Vector3d::Zero();
	double bestCost = std::numeric_limits<double>::infinity();
	for (int mask = 1; mask < 8; mask++)
	{
		std::vector<int> cols;
		for (int j = 0; j < 3; j++)
			if (mask & (1 << j)) cols.push_back(j);
		Eigen::MatrixXd As(A.rows(), cols.size());
		for (size_t j = 0; j < cols.size(); j++) As.col(j) = A.col(cols[j]);
		const Eigen::VectorXd sw = w.cwiseSqrt();
		const Eigen::MatrixXd Aw = sw.asDiagonal() * As;
		const Eigen::VectorXd yw = sw.cwiseProduct(y);
		const Eigen::VectorXd cs = Aw.colPivHouseholderQr().solve(yw);
		if ((cs.array() < 0).any() || !cs.allFinite()) continue;
		Eigen::Vector3d c = Eigen::Vector3d::Zero();
		for (size_t j = 0; j < cols.size(); j++) c[cols[j]] = cs[j];
		const double cost = (sw.cwiseProduct(A * c - y)).squaredNorm();
		if (cost < bestCost)
		{
			bestCost = cost;
			best = c;
		}
	}
	return best;
}

/** Fits var = c0 + c1 d + c2 a to squared errors y (one dof each), with trimming; c0 is
 * kept >= minStd^2 so that a step without motion has a positive variance. */
Eigen::Vector3d fitVariance(const Eigen::MatrixX3d& A, const Eigen::VectorXd& y, double trimChi2,
                            double minStd, double& trimmedFrac)
{
	const Eigen::Index n = A.rows();
	std::vector<bool> use(n, true);
	Eigen::Vector3d c = Eigen::Vector3d::Zero();
	Eigen::VectorXd pred = Eigen::VectorXd::Ones(n);
	for (int round = 0; round < 30; round++)
	{
		const Eigen::Vector3d cPrev = c;
		std::vector<Eigen::Index> idx;
		for (Eigen::Index i = 0; i < n; i++)
			if (use[i]) idx.push_back(i);
		Eigen::MatrixX3d As(idx.size(), 3);
		Eigen::VectorXd ys(idx.size()), ws(idx.size());
		for (size_t j = 0; j < idx.size(); j++)
		{
			As.row(j) = A.row(idx[j]);
			ys[j] = y[idx[j]];
			// IRLS: var(e^2) ~ 2 var^2 for Gaussian e; uniform weights in the first round
			ws[j] = round == 0 ? 1.0 : 1.0 / std::max(1e-30, pred[idx[j]] * pred[idx[j]]);
		}
		c = nnls3(As, ys, ws);
		c[0] = std::max(c[0], minStd * minStd);
		pred = A * c;
		size_t trimmed = 0;
		for (Eigen::Index i = 0; i < n; i++)
		{
			use[i] = pred[i] > 0 && y[i] / pred[i] <= trimChi2;
			if (!use[i]) trimmed++;
		}
		trimmedFrac = n > 0 ? double(trimmed) / n : 0;
		if (round > 1 && (c - cPrev).norm() <= 1e-6 * c.norm()) break;
	}
	return c;
}

void printStats(std::ostream& o, const char* name, const TResidualStats& s, double scale)
{
	o << "  " << std::left << std::setw(22) << name << std::right << " n=" << std::setw(5) << s.n
	  << "  mean=" << std::setw(9) << s.mean * scale << "  std=" << std::setw(9) << s.std * scale
	  << "  median=" << std::setw(9) << s.median * scale << "  robust_std=" << std::setw(9)
	  << s.robust_std * scale << "  outliers=" << std::setw(6) << 100 * s.outlier_fraction << "%"
	  << "  inlier mean=" << std::setw(9) << s.inlier_mean * scale
	  << "  inlier std=" << std::setw(9) << s.inlier_std * scale << "\n";
}
}  // namespace

TResidualStats residualStats(const std::vector<double>& r, double outlierFactor)
{
	TResidualStats s;
	s.n = r.size();
	if (r.empty()) return s;
	meanStd(r, s.mean, s.std);
	s.median = median(r);
	std::vector<double> dev(r.size());
	for (size_t i = 0; i < r.size(); i++) dev[i] = std::abs(r[i] - s.median);
	s.robust_std = 1.482602218505602 * median(dev);
	std::vector<double> in;
	for (size_t i = 0; i < r.size(); i++)
		if (dev[i] <= outlierFactor * s.robust_std) in.push_back(r[i]);
	s.outlier_fraction = 1.0 - double(in.size()) / r.size();
	meanStd(in, s.inlier_mean, s.inlier_std);
	return s;
}

void TNoiseSamples::append(const TNoiseSamples& o)
{
	meas.insert(meas.end(), o.meas.begin(), o.meas.end());
	odo.insert(odo.end(), o.odo.begin(), o.odo.end());
}

TNoiseSamples collectNoiseSamples(const TDataset& d, const TImportResult& res)
{
	std::map<int, CTrajectoryInterpolator> gt;
	for (const auto& [r, rows] : d.groundTruth) gt.emplace(r, CTrajectoryInterpolator(rows));
	const auto& ego = gt.at(d.ego);
	TNoiseSamples s;
	for (const auto& step : res.steps)
		for (const auto& m : step.meas)
		{
			if (!ego.covers(m.t)) continue;
			Eigen::Vector2d q;
			if (isLandmarkSubject(m.subject))
				q = d.landmarks.at(m.subject);
			else
			{
				const auto& tr = gt.at(m.subject);
				if (!tr.covers(m.t)) continue;
				q = tr.at(m.t).head<2>();
			}
			const Eigen::Vector3d p = ego.at(m.t);
			const Eigen::Vector2d dq = q - p.head<2>();
			const double rg = dq.norm();
			const double bg = std::atan2(dq.y(), dq.x()) - p.z();
			s.meas.push_back({d.ego, m.subject, rg, m.range - rg, wrapAngle(m.bearing - bg)});
		}
	for (size_t k = 1; k < res.steps.size(); k++)
	{
		const auto& a = res.steps[k - 1];
		const auto& b = res.steps[k];
		const Eigen::Vector3d gtInc = relativeSE2(ego.at(a.t), ego.at(b.t));
		Eigen::Vector3d e = gtInc - b.increment.delta;
		e.z() = wrapAngle(e.z());
		s.odo.push_back(
		    {d.ego, b.increment.distance, b.increment.angle, b.increment.delta, gtInc, e});
	}
	return s;
}

namespace
{
/** Range and bearing residual statistics: all, per subject kind and per true-range bin. */
void estimateMeasurementNoise(const TNoiseSamples& s, double outlierFactor, TNoiseEstimate& est)
{
	std::vector<double> rA, bA, rL, bL, rR, bR;
	const std::vector<std::pair<double, double>> binEdges = {{0, 2}, {2, 4}, {4, 6}, {6, 100}};
	std::vector<std::vector<double>> rB(binEdges.size()), bB(binEdges.size());
	for (const auto& m : s.meas)
	{
		rA.push_back(m.e_range);
		bA.push_back(m.e_bearing);
		(isLandmarkSubject(m.subject) ? rL : rR).push_back(m.e_range);
		(isLandmarkSubject(m.subject) ? bL : bR).push_back(m.e_bearing);
		for (size_t i = 0; i < binEdges.size(); i++)
			if (m.range_gt >= binEdges[i].first && m.range_gt < binEdges[i].second)
			{
				rB[i].push_back(m.e_range);
				bB[i].push_back(m.e_bearing);
			}
	}
	est.range_all = residualStats(rA, outlierFactor);
	est.bearing_all = residualStats(bA, outlierFactor);
	est.range_landmarks = residualStats(rL, outlierFactor);
	est.bearing_landmarks = residualStats(bL, outlierFactor);
	est.range_robots = residualStats(rR, outlierFactor);
	est.bearing_robots = residualStats(bR, outlierFactor);
	for (size_t i = 0; i < binEdges.size(); i++)
		est.bins.push_back({binEdges[i].first, binEdges[i].second,
		                    residualStats(rB[i], outlierFactor),
		                    residualStats(bB[i], outlierFactor)});
}

/** Odometry noise model fitted to the squared increment errors, with its consistency figures. */
void estimateOdometryNoise(const TNoiseSamples& s, double outlierFactor, double trimChi2,
                           TNoiseEstimate& est)
{
	const Eigen::Index n = static_cast<Eigen::Index>(s.odo.size());
	est.odo_steps = s.odo.size();
	if (n >= 3)
	{
		Eigen::MatrixX3d A(n, 3);
		Eigen::VectorXd yxy(n), yphi(n);
		std::vector<double> ex, ey, ephi;
		double sumGtXY = 0, sumOdoXY = 0, sumGtPhi = 0, sumOdoPhi = 0;
		for (Eigen::Index i = 0; i < n; i++)
		{
			const auto& o = s.odo[i];
			A.row(i) << 1.0, o.distance, o.angle;
			yxy[i] = 0.5 * (o.e.x() * o.e.x() + o.e.y() * o.e.y());
			yphi[i] = o.e.z() * o.e.z();
			ex.push_back(o.e.x());
			ey.push_back(o.e.y());
			ephi.push_back(o.e.z());
			sumGtXY += o.gt.head<2>().norm();
			sumOdoXY += o.odo.head<2>().norm();
			sumGtPhi += std::abs(o.gt.z());
			sumOdoPhi += std::abs(o.odo.z());
		}
		// floors: about the Vicon resolution (0.1 mm, 1e-4 rad)
		const Eigen::Vector3d cxy =
		    fitVariance(A, yxy, trimChi2, 1e-4, est.odo_trimmed_fraction_xy);
		const Eigen::Vector3d cphi =
		    fitVariance(A, yphi, trimChi2, 1e-4, est.odo_trimmed_fraction_phi);
		auto& m = est.odometry;
		m.std_xy_min = std::sqrt(cxy[0]);
		m.var_xy_per_m = cxy[1];
		m.var_xy_per_rad = cxy[2];
		m.std_phi_min = std::sqrt(cphi[0]);
		m.var_phi_per_m = cphi[1];
		m.var_phi_per_rad = cphi[2];
		est.odo_translation_gain = sumOdoXY > 0 ? sumGtXY / sumOdoXY : 0;
		est.odo_rotation_gain = sumOdoPhi > 0 ? sumGtPhi / sumOdoPhi : 0;
		double neesXY = 0, neesPhi = 0;
		size_t aboveXY = 0, abovePhi = 0;
		for (Eigen::Index i = 0; i < n; i++)
		{
			const double vxy = std::max(1e-30, A.row(i).dot(cxy));
			const double vphi = std::max(1e-30, A.row(i).dot(cphi));
			const double nxy = 2 * yxy[i] / vxy;  // chi2 with 2 dof
			const double nphi = yphi[i] / vphi;   // chi2 with 1 dof
			neesXY += nxy;
			neesPhi += nphi;
			if (nxy > 5.991) aboveXY++;
			if (nphi > 3.841) abovePhi++;
		}
		est.odo_mean_nees_xy = neesXY / n;
		est.odo_mean_nees_phi = neesPhi / n;
		est.odo_frac_xy_above_95 = double(aboveXY) / n;
		est.odo_frac_phi_above_95 = double(abovePhi) / n;
		est.odo_ex = residualStats(ex, outlierFactor);
		est.odo_ey = residualStats(ey, outlierFactor);
		est.odo_ephi = residualStats(ephi, outlierFactor);
		estimateOdometryCorrelation(s, trimChi2, est);
	}
}
}  // namespace

TNoiseEstimate estimateNoise(const TNoiseSamples& s, double outlierFactor, double trimChi2)
{
	TNoiseEstimate est;
	est.outlier_factor = outlierFactor;
	estimateMeasurementNoise(s, outlierFactor, est);
	estimateOdometryNoise(s, outlierFactor, trimChi2, est);
	return est;
}

std::string TNoiseEstimate::toText() const
{
	std::ostringstream o;
	o << std::setprecision(4);
	o << "Measurement residuals (measured - ground truth); range in m, bearing in deg; "
	  << "outliers: |r - median| > " << outlier_factor << " robust_std\n";
	const double deg = 180.0 / M_PI;
	printStats(o, "range, all", range_all, 1);
	printStats(o, "range, landmarks", range_landmarks, 1);
	printStats(o, "range, robots", range_robots, 1);
	printStats(o, "bearing, all", bearing_all, deg);
	printStats(o, "bearing, landmarks", bearing_landmarks, deg);
	printStats(o, "bearing, robots", bearing_robots, deg);
	for (const auto& b : bins)
	{
		std::ostringstream nm;
		nm << "range, " << b.lo << "-" << b.hi << " m";
		printStats(o, nm.str().c_str(), b.range, 1);
		std::ostringstream nb;
		nb << "bearing, " << b.lo << "-" << b.hi << " m";
		printStats(o, nb.str().c_str(), b.bearing, deg);
	}
	o << "Odometry increments (ground truth - odometry, frame at t_{k-1}), steps: " << odo_steps
	  << "\n";
	printStats(o, "e_x [m]", odo_ex, 1);
	printStats(o, "e_y [m]", odo_ey, 1);
	printStats(o, "e_phi [deg]", odo_ephi, deg);
	o << "  fitted: var_xy = " << odometry.std_xy_min << "^2 + " << odometry.var_xy_per_m << " d + "
	  << odometry.var_xy_per_rad << " a   (trimmed " << 100 * odo_trimmed_fraction_xy << "%)\n"
	  << "          var_phi = " << odometry.std_phi_min << "^2 + " << odometry.var_phi_per_m
	  << " d + " << odometry.var_phi_per_rad << " a   (trimmed " << 100 * odo_trimmed_fraction_phi
	  << "%)\n"
	  << "  gains (ground truth / odometry): translation " << odo_translation_gain << ", rotation "
	  << odo_rotation_gain << "\n"
	  << "  check with the fit: mean NEES xy = " << odo_mean_nees_xy
	  << " (2 expected), phi = " << odo_mean_nees_phi << " (1 expected); above chi2 95%: xy "
	  << 100 * odo_frac_xy_above_95 << "%, phi " << 100 * odo_frac_phi_above_95
	  << "% (5% expected)\n"
	  << "  correlation of the normalized errors: integrated autocorrelation time tau_xy = "
	  << odo_acf_xy.tau << " (window " << odo_acf_xy.window
	  << (odo_acf_xy.converged ? "" : ", not converged") << "), tau_phi = " << odo_acf_phi.tau
	  << " (window " << odo_acf_phi.window << (odo_acf_phi.converged ? "" : ", not converged")
	  << ")\n  NEES per dof of sums of W increments, white fit (xy / phi):";
	for (size_t i = 0; i < odo_window_nees_xy.size(); i++)
		o << "  W=" << odo_window_lengths[i] << ": " << odo_window_nees_xy[i] << " / "
		  << odo_window_nees_phi[i];
	o << "\n";
	return o.str();
}

std::string TNoiseEstimate::toIni() const
{
	std::ostringstream o;
	o << std::setprecision(3);
	o << "[MRCLAM_Import]\nstd_range = " << range_all.inlier_std
	  << "\nstd_bearing = " << bearing_all.inlier_std
	  << "\nodo_std_xy_min = " << odometry.std_xy_min
	  << "\nodo_var_xy_per_m = " << odometry.var_xy_per_m
	  << "\nodo_var_xy_per_rad = " << odometry.var_xy_per_rad
	  << "\nodo_std_phi_min = " << odometry.std_phi_min
	  << "\nodo_var_phi_per_m = " << odometry.var_phi_per_m
	  << "\nodo_var_phi_per_rad = " << odometry.var_phi_per_rad
	  << "\nodo_noise_model = inflated\nodo_tau_xy = " << odometry.tau_xy
	  << "\nodo_tau_phi = " << odometry.tau_phi << "\n";
	if (delay_estimate >= 0) o << "odo_delay = " << delay_estimate << "\n";
	if (scale_v_estimate > 0) o << "odo_scale_v = " << scale_v_estimate << "\n";
	return o.str();
}
}  // namespace dynslam::mrclam
