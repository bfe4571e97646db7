#include <dynslam/common/seam_options.h>

namespace dynslam
{
estimator::TObjectMotionParams objectMotionParams(const TModelOptions& o)
{
	estimator::TObjectMotionParams p;
	p.smoothing = o.smoothing;
	p.Sigma_s = o.Sigma_s;
	p.cv = o.cv;
	p.cv.gate = estimator::gateThreshold2Dof(o.cv_gate);
	return p;
}

estimator::TUpdateEngineParams updateEngineParams(const TModelOptions& o)
{
	estimator::TUpdateEngineParams p;
	p.gate_probability = o.innovation_gate;
	p.robust_c = o.robust_kernel_c;
	p.robust_iterations = o.robust_iterations;
	p.recovery = {o.recovery_count, o.recovery_inflation, o.recovery_min_updates};
	return p;
}

std::string stateLifecycleName(const TModelOptions& o)
{
	return o.compressed_static_update ? "compressed" : "full";
}

estimator::TLifecycleParams lifecycleParams(const TModelOptions& o)
{
	return {o.compressed_passive_after, o.compressed_batch};
}
}  // namespace dynslam
