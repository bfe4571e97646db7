#pragma once
/** The world of the soak tests: the endless straight track of bench/synthetic_world.h (a static
 * landmark every 10 m, IDs in order so none comes back; the ego 5 m per step; 3 rigid objects in
 * convoy), and the dynamic EKF configured for it (Cartesian model with the world's noise, the
 * sparse update, static landmarks dropped after 5 unseen steps). Each test sets the rest
 * (smoothing, K, record_dropped) and calls reset(). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include "synthetic_world.h"

namespace dynslam_test
{
inline dynslam_bench::TSyntheticOptions straightTrack(unsigned seed)
{
	dynslam_bench::TSyntheticOptions o;
	o.track = dynslam_bench::TSyntheticOptions::Track::Straight;
	o.spacing = 10;
	o.step_length = 5;
	o.objects = 3;
	o.seed = seed;
	return o;
}

inline void configureForStraightTrack(dynslam::CDynamicKFSLAM2D& f,
                                      const dynslam_bench::TSyntheticOptions& o)
{
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = dynslam::models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0 = o.Sigma_w;
	f.options.drop_static_after_unseen_steps = 5;
	f.options.sparse_static_update = true;
}
}  // namespace dynslam_test
