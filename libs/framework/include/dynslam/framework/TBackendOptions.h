#pragma once
/** @file TBackendOptions.h
 * Options of the framework's back-ends (doc/backends.md). The model (noise covariances,
 * measurement model, prior, drop policies) is the dynamic EKF's: TModelOptions (dynslam::common),
 * read from the section named by `model_section` (default [DynamicKFSLAM]), so one INI
 * configures the EKF and every back-end alike. */
#include <dynslam/common/model_options.h>
#include <mrpt/config/CLoadableOptions.h>

#include <string>

namespace dynslam::framework
{
/** The object-pose residual (doc/framework.md, "The object-pose residual"). */
enum class PoseResidual
{
	PoseSpace,    ///< xi (-) gamma(f0, ft), Gamma2 diag(Sigma_xi) Gamma2^T: exactly Alg. 4
	FeatureSpace  ///< f_t - g^o(xi, f0), Sigma_xi per feature: the paper's Theorem 4.1 form
};

struct TBackendOptions : public mrpt::config::CLoadableOptions
{
	/** Reads [section]: backend, model_section, window_size, max_iterations, tolerance,
	 * pose_residual, object_features, solver; then the model from [model_section]. Unknown
	 * keys and invalid values throw std::invalid_argument naming [section] key = value. */
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
	                        const std::string& section) override;
	void dumpToTextStream(std::ostream& out) const override;
	/** Throws std::invalid_argument naming the offending option. */
	void validate() const;

	/** backend = alg1 | vdo | dynaslam2 | cubeslam | clusterslam_decoupled |
	 * clusterslam_semidecoupled. */
	std::string backend = "alg1";
	std::string model_section = "DynamicKFSLAM";
	TModelOptions model;
	/** Ego poses kept in the window (>= 1); 0 in the INI is rejected; "all" (stored as -1)
	 * keeps the whole horizon (vdo's default). alg1 keeps 1 (the EKF). */
	int window_size = 10;
	int max_iterations = 10;  ///< GN iterations per step (smoothers); alg1: 1 per sub-step
	double tolerance = 1e-9;  ///< stop when max |delta| < tolerance
	PoseResidual pose_residual = PoseResidual::PoseSpace;
	/** What happens to a time-t object feature once its pose is in the window:
	 * keep (vdo) or marginalize (dynaslam2). `drop` is rejected by validate(): dropping f_t
	 * removes every term touching it, including the only residual on xi_t. */
	enum class FeaturePolicy
	{
		Keep,
		Marginalize,
		Drop
	} object_features = FeaturePolicy::Keep;
	int solver = 0;  ///< 0 auto, 1 dense, 2 sparse
};

/** The defaults of each back-end kind (before the INI overrides them). */
TBackendOptions defaultBackendOptions(const std::string& kind);
/** The kinds makeBackend() knows. */
const std::vector<std::string>& backendKinds();
}  // namespace dynslam::framework
