#pragma once
/** @file noise_estimation.h
 * Noise parameters of the MRCLAM data estimated from its Vicon ground truth (issue 7, item 3).
 * Pure C++/Eigen. Method (also in doc/results/real-data.md):
 *
 * Measurements: for every kept measurement (import.h rules) at its own time t, the ego pose
 * p(t) and the subject's position q(t) (landmark: surveyed position; robot: Vicon, interpolated)
 * give the predicted range |q - p| and bearing atan2(q - p) - theta. Residuals = measured -
 * predicted (bearing wrapped). Statistics: mean, std, median, robust std = 1.4826 MAD, outlier
 * fraction (|r - median| > k * robust std), and mean/std of the inliers; separately for
 * landmarks and robots and in range bins.
 *
 * Odometry: for every step k >= 1 of the import, e = (ground-truth increment) - (integrated
 * odometry increment), componentwise in the robot frame at t_{k-1}, angle wrapped. The model
 * of odometry.h, var = c0 + c_d * distance + c_a * angle, is fitted by non-negative least
 * squares of (e_x^2 + e_y^2) / 2 (resp. e_phi^2) on (1, distance, angle); samples with a
 * normalized squared error above trim_chi2 are trimmed and the fit repeated (up to 30 rounds
 * until it converges, the later ones weighted by 1/var^2: iteratively reweighted least squares,
 * whose fixed point is the Gaussian maximum-likelihood fit of the inliers). The floors c0 >=
 * (1e-4)^2 (m^2, rad^2; the Vicon resolution) keep a step without motion at a positive variance.
 *
 * Odometry delay: the increments over the import's step intervals are recomputed for a grid
 * of delays d (odometry.h); the d with the smallest RMS heading error against the ground
 * truth is the estimate (scoreOdometryDelays; pooled over robots by summing squared errors).
 * Gains: sum |dtheta_gt| / sum |dtheta_odo| and sum |dp_gt| / sum |dp_odo| over the steps
 * (1 = no scale error; reported, not corrected).
 *
 * Odometry correlation (odometry_autocorr.cpp): the errors normalized by the fitted model,
 * z_k = e_k / sqrt(var_k) (heading; x and y as two series), per robot in step order, clipped
 * to +-sqrt(trim_chi2). Their integrated autocorrelation time tau = 1 + 2 sum_{l=1}^{M} rho(l)
 * (Sokal's window: the smallest M >= 5 tau(M)) is the factor by which the variance of a sum of
 * many increments exceeds the white model's; it is the inflation of TOdometryNoiseModel's
 * `inflated` model. Check: the NEES of sums of W consecutive increments under the white model
 * (about tau for W much longer than the correlation). */
#include <dynslam/mrclam/import.h>
#include <dynslam/mrclam/mrclam_files.h>
#include <dynslam/mrclam/odometry.h>

#include <string>
#include <vector>

namespace dynslam::mrclam
{
struct TResidualStats
{
	size_t n = 0;
	double mean = 0, std = 0, median = 0, robust_std = 0;
	double outlier_fraction = 0;
	double inlier_mean = 0, inlier_std = 0;
};
/** Statistics of residuals r; outliers: |r - median| > outlierFactor * robust_std. */
TResidualStats residualStats(const std::vector<double>& r, double outlierFactor);

/** Integrated autocorrelation time of zero-mean series pooled over independent series (the
 * normalized errors are zero-mean under the model, so no mean is removed: a bias that lasts
 * counts as correlation): rho(l) = [sum z_k z_{k+l} / N_l] / [sum z_k^2 / N],
 * tau(M) = 1 + 2 sum_{l=1}^{M} rho(l), M = the smallest lag with M >= c tau(M) (Sokal), at most
 * maxLag (then converged = false). Throws std::invalid_argument for c <= 0 or maxLag < 1. */
struct TAutocorrelation
{
	size_t n = 0;             ///< samples in all series
	double tau = 1;           ///< [steps]
	int window = 0;           ///< M
	bool converged = false;   ///< a window M <= maxLag was found
	std::vector<double> rho;  ///< rho(0..M)
};
TAutocorrelation integratedAutocorrelation(const std::vector<std::vector<double>>& series,
                                           double c = 5, int maxLag = 400);

/** Raw residual samples, appendable over several robots. */
struct TNoiseSamples
{
	struct TMeas
	{
		int ego, subject;
		double range_gt, e_range, e_bearing;
	};
	struct TOdo
	{
		int ego;
		double distance, angle;
		Eigen::Vector3d odo;  ///< integrated odometry increment
		Eigen::Vector3d gt;   ///< ground-truth increment
		Eigen::Vector3d e;    ///< gt - odo, angle wrapped
	};
	std::vector<TMeas> meas;
	std::vector<TOdo> odo;
	void append(const TNoiseSamples& o);
};

/** Residuals of one imported robot (`res` from importRobot on `data`). */
TNoiseSamples collectNoiseSamples(const TDataset& data, const TImportResult& res);

struct TNoiseEstimate
{
	double outlier_factor = 5;
	TResidualStats range_all, bearing_all, range_landmarks, bearing_landmarks, range_robots,
	    bearing_robots;
	struct TBin
	{
		double lo, hi;
		TResidualStats range, bearing;
	};
	std::vector<TBin> bins;  ///< by ground-truth range
	// odometry
	size_t odo_steps = 0;
	TOdometryNoiseModel odometry;  ///< fitted model
	double odo_trimmed_fraction_xy = 0, odo_trimmed_fraction_phi = 0;
	double odo_translation_gain = 0;                     ///< sum |dp_gt| / sum |dp_odo|
	double odo_rotation_gain = 0;                        ///< sum |dtheta_gt| / sum |dtheta_odo|
	double odo_mean_nees_xy = 0, odo_mean_nees_phi = 0;  ///< E[e^2/var] with the fit (all)
	double odo_frac_xy_above_95 = 0, odo_frac_phi_above_95 = 0;  ///< chi2 95% exceedance
	TResidualStats odo_ex, odo_ey, odo_ephi;
	/** Correlation of the normalized errors (x and y pooled; heading) and the inflation
	 * factors tau_xy, tau_phi of odometry.h's inflated model (copied into `odometry`). */
	TAutocorrelation odo_acf_xy, odo_acf_phi;
	/** NEES per dof of sums of W consecutive increment errors under the white fit, for the W
	 * of odo_window_lengths (1 if the white model held over W steps). */
	std::vector<int> odo_window_lengths{1, 10, 30, 100};
	std::vector<double> odo_window_nees_xy, odo_window_nees_phi;
	std::string toText() const;
	/** The chosen values as INI lines for [MRCLAM_Import] (with odo_noise_model = inflated
	 * and the taus; and, if set, odo_delay and odo_scale_v from delay_estimate and
	 * scale_v_estimate). */
	std::string toIni() const;
	double delay_estimate = -1;    ///< [s] set by the caller (< 0: not written by toIni)
	double scale_v_estimate = -1;  ///< set by the caller (< 0: not written by toIni)
};

/** Score of one odometry delay over the step intervals of an import. */
struct TDelayScore
{
	double delay = 0;                ///< [s]
	size_t n = 0;                    ///< step intervals
	double sse_phi = 0, sse_xy = 0;  ///< sums of squared heading [rad^2] / position [m^2] errors
	double rmsPhi() const;
	double rmsXY() const;
};
/** For each delay: the errors of the increments integrated with it (and the gains) vs the
 * ground truth. */
std::vector<TDelayScore> scoreOdometryDelays(const TDataset& data, const TImportResult& res,
                                             const std::vector<double>& delays, double scaleV = 1,
                                             double scaleW = 1);
/** Adds b's sums to a (same delays, pooling robots). */
void poolDelayScores(std::vector<TDelayScore>& a, const std::vector<TDelayScore>& b);
/** The entry with the smallest sse_phi. */
TDelayScore bestDelay(const std::vector<TDelayScore>& scores);
std::string delayScoresText(const std::vector<TDelayScore>& scores);

/** Dead reckoning of an import: the step increments composed from the ground-truth pose at
 * step 0, with the covariance propagated (F P F^T + G Q G^T), compared with the ground truth
 * at the last step at or before t_0 + T for each T. */
struct TDeadReckoningPoint
{
	double T = 0;              ///< [s] after the first step
	double error = 0;          ///< position error [m]
	double sigma = 0;          ///< sqrt(trace of the propagated position covariance) [m]
	double path = 0;           ///< ground-truth path length up to there [m]
	double heading_error = 0;  ///< [rad]
};
std::vector<TDeadReckoningPoint> deadReckoning(const TImportResult& res,
                                               const std::vector<double>& times);
std::string deadReckoningText(const std::vector<TDeadReckoningPoint>& pts);

/** Fills odo_acf_* and odo_window_nees_* of est (whose white fit est.odometry must be set)
 * and sets est.odometry.tau_xy/tau_phi (>= 1); samples of one robot must be contiguous and in
 * step order (collectNoiseSamples, append). */
void estimateOdometryCorrelation(const TNoiseSamples& s, double trimChi2, TNoiseEstimate& est);

TNoiseEstimate estimateNoise(const TNoiseSamples& s, double outlierFactor = 5,
                             double trimChi2 = 25);
}  // namespace dynslam::mrclam
