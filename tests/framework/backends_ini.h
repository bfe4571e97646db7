#pragma once
/** @file backends_ini.h
 * The INI text shared by the back-end tests (no includes: usable without the EKF). */

namespace dynslam_test
{
/** The INI of the back-end tests on the highway: Cartesian model, the dataset's Sigma_v, a
 * small prior, window 5 for the windowed back-ends. */
inline constexpr const char* kBackendsIni =
    "[DynamicKFSLAM]\n"
    "measurement_model = cartesian\n"
    "Sigma_v = [1e-5 1e-5]\n"
    "motion_noise = action\n"
    "Sigma_0 = [1e-6 1e-6 1e-8]\n"
    "Sigma_xi = [0.1 0.1]\n"
    "[Framework]\n"
    "window_size = 5\n";
}  // namespace dynslam_test
