#include <dynslam/common/config_utils.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/framework/TBackendOptions.h>

#include <algorithm>
#include <ostream>
#include <stdexcept>

namespace dynslam::framework
{
const std::vector<std::string>& backendKinds()
{
	static const std::vector<std::string> k{"alg1",
	                                        "vdo",
	                                        "dynaslam2",
	                                        "cubeslam",
	                                        "clusterslam_decoupled",
	                                        "clusterslam_semidecoupled"};
	return k;
}

TBackendOptions defaultBackendOptions(const std::string& kind)
{
	if (std::find(backendKinds().begin(), backendKinds().end(), kind) == backendKinds().end())
		throw std::invalid_argument("unknown back-end '" + kind + "'");
	TBackendOptions o;
	o.backend = kind;
	if (kind == "alg1")
	{
		o.window_size = 1;
		o.max_iterations = 1;
	}
	else if (kind == "vdo")
	{
		o.window_size = -1;  // the whole horizon
		o.pose_residual = PoseResidual::FeatureSpace;
		o.object_features = TBackendOptions::FeaturePolicy::Keep;
	}
	else if (kind == "dynaslam2")
	{
		o.pose_residual = PoseResidual::FeatureSpace;
		o.object_features = TBackendOptions::FeaturePolicy::Marginalize;
	}
	else  // cubeslam, clusterslam_*
	{
		o.pose_residual = PoseResidual::FeatureSpace;
		o.object_features = TBackendOptions::FeaturePolicy::Marginalize;
	}
	return o;
}

void TBackendOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                         const std::string& s)
{
	using namespace dynslam::config;
	rejectUnknownKeys(c, s,
	                  {"backend", "model_section", "window_size", "max_iterations", "tolerance",
	                   "pose_residual", "object_features", "solver"});
	// backend: optional when the caller already chose the kind (defaultBackendOptions(kind)).
	const int current = int(std::find(backendKinds().begin(), backendKinds().end(), backend) -
	                        backendKinds().begin());
	const int k = readChoice(c, s, "backend", backendKinds(), current);
	*this = defaultBackendOptions(backendKinds()[k]);
	model_section = readString(c, s, "model_section", model_section);
	if (has(c, s, "window_size"))
	{
		const std::string v = readString(c, s, "window_size", "");
		if (v == "all")
			window_size = -1;
		else
		{
			window_size = int(readInt(c, s, "window_size", window_size));
			if (window_size < 1) fail(s, "window_size", v, "must be >= 1 (or 'all')");
		}
	}
	max_iterations = int(readInt(c, s, "max_iterations", max_iterations));
	if (max_iterations < 1)
		fail(s, "max_iterations", std::to_string(max_iterations), "must be >= 1");
	tolerance = readPositive(c, s, "tolerance", tolerance);
	pose_residual = readChoice(c, s, "pose_residual", {"pose_space", "feature_space"},
	                           pose_residual == PoseResidual::PoseSpace ? 0 : 1) == 0
	                    ? PoseResidual::PoseSpace
	                    : PoseResidual::FeatureSpace;
	object_features = TBackendOptions::FeaturePolicy(
	    readChoice(c, s, "object_features", {"keep", "marginalize", "drop"}, int(object_features)));
	solver = readChoice(c, s, "solver", {"auto", "dense", "sparse"}, solver);
	model.loadFromConfigFile(c, model_section);
	try
	{
		validate();
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument("[" + s + "] " + e.what());
	}
}

void TBackendOptions::validate() const
{
	if (window_size == 0 || window_size < -1)
		throw std::invalid_argument("window_size = " + std::to_string(window_size) +
		                            ": must be >= 1 (or 'all')");
	if (max_iterations < 1) throw std::invalid_argument("max_iterations must be >= 1");
	if (object_features == FeaturePolicy::Drop)
		throw std::invalid_argument(
		    "object_features = drop: dropping f_t removes every term touching it, including the "
		    "only residual on the object pose xi_t, which would be left unobservable; use "
		    "marginalize (keeps its information) or keep");
	if (!(tolerance > 0)) throw std::invalid_argument("tolerance must be > 0");
	if (!model.prior_gauge_anchor && model.Sigma_0.determinant() <= 0)
		throw std::invalid_argument(
		    "the framework needs a positive-definite Sigma_0 ([" + model_section +
		    "] Sigma_0): its running cost starts with ||x_0 - mu_0||^2_{Sigma_0^-1}");
	if (model.prior_gauge_anchor && backend != "alg1")
		throw std::invalid_argument(
		    "[" + model_section +
		    "] prior_gauge = anchor: the anchored prior (x_0 fixed, Sigma_0 "
		    "only in the reported covariances) is implemented in the dynamic EKF and Alg. 1 "
		    "(backend = alg1) only; backend = " +
		    backend + " needs prior_gauge = prior");
	if (model.prune_min_sightings > 0 && backend != "alg1")
		throw std::invalid_argument(
		    "[" + model_section +
		    "] prune_min_sightings = " + std::to_string(model.prune_min_sightings) +
		    ": pruning is implemented in the dynamic EKF and Alg. 1 (backend = alg1) only; "
		    "backend = " +
		    backend + " needs prune_min_sightings = 0");
	if (model.drop_object_after_unseen_steps > 0)
		throw std::invalid_argument("[" + model_section + "] drop_object_after_unseen_steps = " +
		                            std::to_string(model.drop_object_after_unseen_steps) +
		                            ": implemented in the dynamic EKF only; the framework "
		                            "back-ends need 0");
	if (model.fuse_landmarks_prob != 0)
		throw std::invalid_argument("[" + model_section + "] fuse_landmarks_prob = " +
		                            std::to_string(model.fuse_landmarks_prob) +
		                            ": landmark fusion is implemented in the dynamic EKF only; "
		                            "the framework back-ends need 0");
	if (model.odometry_bias.enabled())
		throw std::invalid_argument(
		    "[" + model_section + "] odometry_bias = " + model.odometry_bias.mode +
		    ": online odometry bias estimation is implemented in the dynamic EKF only "
		    "(CDynamicKFSLAM2D); the framework back-ends need odometry_bias = none");
	if (estimator::routers().caps(model.feature_labels).classifies)
		throw std::invalid_argument(
		    "[" + model_section + "] feature_labels = " + model.feature_labels +
		    ": classification of anonymous tracks is implemented in the dynamic EKF only "
		    "(CDynamicKFSLAM2D, doc/results/classification.md); the framework back-ends need "
		    "feature_labels = ids");
	model.validate();
}

void TBackendOptions::dumpToTextStream(std::ostream& out) const
{
	out << "\n----------- [dynslam::framework::TBackendOptions] ------------\n\n";
	out << "backend         = " << backend << "\n";
	out << "model_section   = " << model_section << "\n";
	out << "window_size     = "
	    << (window_size < 0 ? std::string("all") : std::to_string(window_size)) << "\n";
	out << "max_iterations  = " << max_iterations << "\n";
	out << "tolerance       = " << tolerance << "\n";
	out << "pose_residual   = "
	    << (pose_residual == PoseResidual::PoseSpace ? "pose_space" : "feature_space") << "\n";
	static const char* fp[] = {"keep", "marginalize", "drop"};
	out << "object_features = " << fp[int(object_features)] << "\n";
	static const char* sv[] = {"auto", "dense", "sparse"};
	out << "solver          = " << sv[solver] << "\n";
	model.dumpToTextStream(out);
}
}  // namespace dynslam::framework
