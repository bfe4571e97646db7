#include <dynslam/estimator/box_router.h>
#include <dynslam/estimator/classifying_router.h>
#include <dynslam/estimator/constant_acceleration.h>
#include <dynslam/estimator/constant_turn_rate.h>
#include <dynslam/estimator/multiple_model.h>
#include <dynslam/estimator/seam_registries.h>

namespace dynslam::estimator
{
const CRouterRegistry& routers()
{
	static const CRouterRegistry r = []
	{
		CRouterRegistry g("feature_labels");
		g.add("ids", [](const TRouterParams&) { return std::make_unique<CIdRangeRouter>(); }, {});
		g.add("classify",
		      [](const TRouterParams& p) {
			      return std::make_unique<CClassifyingRouter>(p.classify ? *p.classify
			                                                             : TClassifyParams());
		      },
		      {true});
		g.add("boxes",
		      [](const TRouterParams& p)
		      {
			      return std::make_unique<CBoxRouter>(p.boxes ? *p.boxes : TBoxTrackerParams(),
			                                          p.classify ? *p.classify : TClassifyParams());
		      },
		      {true});
		return g;
	}();
	return r;
}

const CObjectMotionRegistry& objectMotionModels()
{
	static const CObjectMotionRegistry r = []
	{
		CObjectMotionRegistry g("object_model");
		TObjectMotionCaps smoothing, objectCentric;
		smoothing.smoothing = true;
		objectCentric.object_centric = true;
		objectCentric.window = false;  // the EKF and Alg. 1 only
		g.add("paper",
		      [](const TObjectMotionParams& p) -> std::unique_ptr<IObjectMotionModel>
		      {
			      if (p.smoothing) return std::make_unique<CPaperSmoothing>(p.Sigma_s);
			      return std::make_unique<CNoObjectMotion>();
		      },
		      {});
		g.add(
		    "paper_smoothing",
		    [](const TObjectMotionParams& p)
		    { return std::make_unique<CPaperSmoothing>(p.Sigma_s); },
		    smoothing);
		g.add(
		    "cv",
		    [](const TObjectMotionParams& p) { return std::make_unique<CConstantVelocity>(p.cv); },
		    objectCentric);
		g.add(
		    "ctrv",
		    [](const TObjectMotionParams& p) { return std::make_unique<CConstantTurnRate>(p.cv); },
		    objectCentric);
		TObjectMotionCaps ca = objectCentric;
		ca.noise_key = "ca_jerk_psd";
		g.add(
		    "ca",
		    [](const TObjectMotionParams& p)
		    { return std::make_unique<CConstantAcceleration>(p.cv); },
		    ca);
		g.add(
		    "mm",
		    [](const TObjectMotionParams& p) { return std::make_unique<CMultipleModel>(p.cv); },
		    objectCentric);
		return g;
	}();
	return r;
}

const CUpdateEngineRegistry& updateEngines()
{
	static const CUpdateEngineRegistry r = []
	{
		CUpdateEngineRegistry g("outlier_method");
		const auto sparse = [](const TUpdateEngineParams&)
		{ return std::make_unique<CSparseUpdateEngine>(); };
		g.add("gate", sparse, {});
		g.add("none", sparse, {false});
		for (const auto& [name, kernel] :
		     {std::pair{"huber", RobustKernel::Huber}, std::pair{"cauchy", RobustKernel::Cauchy}})
			g.add(name,
			      [k = kernel](const TUpdateEngineParams& p) {
				      return std::make_unique<CRobustUpdateEngine>(k, p.robust_c,
				                                                   p.robust_iterations);
			      },
			      {});
		g.add("gate_recovery",
		      [](const TUpdateEngineParams& p)
		      { return std::make_unique<CGateRecoveryUpdateEngine>(p.recovery); },
		      {true, true});
		return g;
	}();
	return r;
}

const CLifecycleRegistry& stateLifecycles()
{
	static const CLifecycleRegistry r = []
	{
		CLifecycleRegistry g("state_lifecycle");
		g.add("full",
		      [](const TLifecycleParams&) { return std::make_unique<CFullStateLifecycle>(); },
		      {false});
		g.add("compressed",
		      [](const TLifecycleParams& p)
		      { return std::make_unique<CCompressedLifecycle>(p.passive_after, p.batch); },
		      {true});
		return g;
	}();
	return r;
}
}  // namespace dynslam::estimator
