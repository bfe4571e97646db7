/** TModelOptions: reading, validation and dump of section [DynamicKFSLAM] and the module
 * sections [ObjectModel], [OdometryBias], [Classify] (model_keys.h). */
#include <dynslam/common/box_tracker_options.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/common/model_keys.h>
#include <dynslam/common/model_options.h>
#include <dynslam/estimator/seam_registries.h>

#include <ostream>
#include <stdexcept>
#include <vector>

namespace dynslam
{
// ------------------------------------------------------------------------------------------
// Options
// ------------------------------------------------------------------------------------------
namespace
{
/** Every key of [s] and of the module sections is known and in its own section: a module key in
 * [s] (an INI written before the modules had their sections) names the section it moved to. */
void checkSections(const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	const auto misplaced = [&](const std::string& section, const std::string& verb)
	{
		std::vector<std::string> keys;
		c.getAllKeys(section, keys);
		for (const std::string& k : keys)
		{
			const std::string home = sectionOfKey(k);
			const bool mine = home == (section == s ? std::string(kCoreSection) : section);
			if (!home.empty() && !mine)
				throw std::invalid_argument("[" + section + "] key " + k + " " + verb +
				                            " section [" + (home == kCoreSection ? s : home) +
				                            "] (doc/configuration.md)");
		}
	};
	misplaced(s, "moved to");
	config::rejectUnknownKeys(c, s, sectionKeyNames(kCoreSection));
	for (const std::string& m : moduleSections())
	{
		misplaced(m, "belongs to");
		config::rejectUnknownKeys(c, m, sectionKeyNames(m));
	}
}

/** object_model ([s]), the cv_*, ca_* and mm_* keys ([ObjectModel]; issue 13); paper_smoothing is
 * smoothing = true. */
void loadObjectModel(TModelOptions& o, const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	using namespace dynslam::config;
	const std::vector<std::string> objectModels = estimator::objectMotionModels().names();
	o.object_model = objectModels[size_t(readChoice(c, s, "object_model", objectModels, 0))];
	if (o.object_model == "paper_smoothing")
	{
		if (c.keyExists(s, "smoothing") && !o.smoothing)
			throw std::invalid_argument(
			    "[" + s + "] object_model = paper_smoothing contradicts smoothing = false");
		o.smoothing = true;
	}
	else if (o.object_model == "paper" && o.smoothing)
		o.object_model = "paper_smoothing";
	const bool cvModel = o.objectCentric();
	const std::string m = kObjectModelSection;
	o.cv.dt = readPositive(c, m, "cv_dt", o.cv.dt, cvModel);
	o.cv.accel_psd = readVector(c, m, "cv_accel_psd", o.cv.accel_psd, 3);
	o.cv.velocity_prior_std = readVector(c, m, "cv_velocity_prior_std", o.cv.velocity_prior_std, 3);
	o.cv.jerk_psd = readVector(c, m, "ca_jerk_psd", o.cv.jerk_psd, 3);
	o.cv.accel_prior_std = readVector(c, m, "ca_accel_prior_std", o.cv.accel_prior_std, 3);
	o.cv.mm_switch_prob = readNonNegative(c, m, "mm_switch_prob", o.cv.mm_switch_prob);
	o.cv.mm_manoeuvre_psd = readVector(c, m, "mm_manoeuvre_psd", o.cv.mm_manoeuvre_psd, 3);
	o.cv_gate = readNonNegative(c, m, "cv_gate", o.cv_gate);
	o.cv.fallback_steps = int(readInt(c, m, "cv_fallback_steps", o.cv.fallback_steps));
	o.cv.heading_inflation = readNonNegative(c, m, "cv_heading_inflation", o.cv.heading_inflation);
}
}  // namespace

namespace
{
/** feature_labels = boxes: the box front-end's tracker, section [BoxTracker] (the same keys and
 * defaults as dynslam-compare's tracker_baseline row: box_tracker_options.h). */
TBoxTrackerOptions loadBoxTracker(const mrpt::config::CConfigFileBase& c)
{
	TBoxTrackerOptions b;
	b.loadFromConfigFile(c, "BoxTracker");
	return b;
}

/** feature_labels ([core]) and the classify_* keys ([Classify]; issue 12). */
void loadClassify(TModelOptions& o, const mrpt::config::CConfigFileBase& c, const std::string& core)
{
	using namespace dynslam::config;
	const std::vector<std::string> labels{"ids", "classify", "boxes"};
	o.feature_labels = labels[size_t(readChoice(c, core, "feature_labels", labels, 0))];
	const std::string s = kClassifySection;
	estimator::TClassifyParams& p = o.classify;
	p.alpha = readDouble(c, s, "classify_alpha", p.alpha);
	p.beta = readDouble(c, s, "classify_beta", p.beta);
	p.motion_std = readDouble(c, s, "classify_motion_std", p.motion_std);
	p.max_window = int(readInt(c, s, "classify_max_window", p.max_window));
	p.forget_steps = int(readInt(c, s, "classify_forget_steps", p.forget_steps));
	p.group_prob = readDouble(c, s, "classify_group_prob", p.group_prob);
	p.group_max_dist = readDouble(c, s, "classify_group_max_dist", p.group_max_dist);
	p.reclassify_count = int(readInt(c, s, "classify_reclassify_count", p.reclassify_count));
	p.reclassify_gate = readDouble(c, s, "classify_reclassify_gate", p.reclassify_gate);
	p.candidate_landmarks = readBool(c, s, "classify_candidate_landmarks", p.candidate_landmarks);
	p.surgery = readChoice(c, s, "classify_reclassify", {"surgery", "restart"}, 0) == 0;
	p.stop_count = int(readInt(c, s, "classify_stop_count", p.stop_count));
	p.reuse_gap = int(readInt(c, s, "classify_reuse_gap", p.reuse_gap));
	p.split_count = int(readInt(c, s, "classify_split_count", p.split_count));
	p.join = readBool(c, s, "classify_join", p.join);
	p.use_hints = readBool(c, s, "classify_use_hints", p.use_hints);
	using Link = estimator::TClassifyParams::Link;
	const int link = int(readChoice(c, s, "classify_link", {"off", "hints", "all"}, 1));
	p.link = link == 0 ? Link::Off : link == 1 ? Link::Hints : Link::All;
	p.link_gap = int(readInt(c, s, "classify_link_gap", p.link_gap));
	p.merge_linked = readBool(c, s, "classify_merge_linked", p.merge_linked);
	p.merge_live = readBool(c, s, "classify_merge_live", p.merge_live);
	p.merge_live_window = int(readInt(c, s, "classify_merge_live_window", p.merge_live_window));
	using Test = estimator::TClassifyParams::StaticTest;
	p.static_test = readChoice(c, s, "classify_static_test", {"robot", "map"}, 0) == 0 ? Test::Robot
	                                                                                   : Test::Map;
	// ID -1 readings (estimator/unknown_id_association.h): MRPT's data_assoc_* names and values.
	estimator::TUnknownIdParams& a = p.assoc;
	const std::vector<std::string> methods{"assocNN", "assocJCBB"};
	const std::vector<std::string> metrics{"metricMaha", "metricML"};
	a.method = methods[size_t(readChoice(c, s, "classify_assoc_method", methods, 0))];
	a.metric = metrics[size_t(readChoice(c, s, "classify_assoc_metric", metrics, 0))];
	a.IC_chi2_thres = readDouble(c, s, "classify_assoc_IC_chi2_thres", a.IC_chi2_thres);
	a.IC_metric = metrics[size_t(readChoice(c, s, "classify_assoc_IC_metric", metrics, 0))];
	a.IC_ml_threshold = readDouble(c, s, "classify_assoc_IC_ml_threshold", a.IC_ml_threshold);
	a.moving_gate = readDouble(c, s, "classify_assoc_moving_gate", a.moving_gate);
	a.max_step = readDouble(c, s, "classify_assoc_max_step", a.max_step);
}
}  // namespace

void TModelOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	using namespace dynslam::config;
	checkSections(c, s);  // the descriptor table, model_keys.h
	measurement_model =
	    readChoice(c, s, "measurement_model", {"cartesian", "range_bearing"}, 0, true) == 0
	        ? models::MeasurementModel::Cartesian
	        : models::MeasurementModel::RangeBearing;
	Sigma_v = readCovariance(c, s, "Sigma_v", Sigma_v, 2, true);
	motion_noise_from_action = readChoice(c, s, "motion_noise", {"action", "config"}, 0) == 0;
	Sigma_w = readCovariance(c, s, "Sigma_w", Sigma_w, 3, !motion_noise_from_action);
	initial_pose = readVector(c, s, "initial_pose", initial_pose, 3);
	Sigma_0 = readCovariance(c, s, "Sigma_0", Sigma_0, 3, false, true);
	prior_gauge_anchor =
	    readChoice(c, s, "prior_gauge", {"prior", "anchor"}, prior_gauge_anchor ? 1 : 0) == 1;
	Sigma_xi = readCovariance(c, s, "Sigma_xi", Sigma_xi, 2);
	smoothing = readBool(c, s, "smoothing", smoothing);
	loadObjectModel(*this, c, s);
	Sigma_s = readCovariance(c, s, "Sigma_s", Sigma_s, 3, smoothing);
	drop_time_t_features = readBool(c, s, "drop_time_t_features", drop_time_t_features);
	keep_last_poses = int(readInt(c, s, "keep_last_poses", keep_last_poses));
	drop_static_after_unseen_steps =
	    int(readInt(c, s, "drop_static_after_unseen_steps", drop_static_after_unseen_steps));
	prune_min_sightings = int(readInt(c, s, "prune_min_sightings", prune_min_sightings));
	prune_window = int(readInt(c, s, "prune_window", prune_window));
	drop_object_after_unseen_steps =
	    int(readInt(c, s, "drop_object_after_unseen_steps", drop_object_after_unseen_steps));
	fuse_landmarks_prob = readDouble(c, s, "fuse_landmarks_prob", fuse_landmarks_prob);
	skip_prediction_on_empty_map =
	    readBool(c, s, "skip_prediction_on_empty_map", skip_prediction_on_empty_map);
	{
		const int u = readChoice(c, s, "static_update", {"mrpt", "sparse", "compressed"},
		                         compressed_static_update ? 2
		                         : sparse_static_update   ? 1
		                                                  : 0);
		sparse_static_update = u >= 1;
		compressed_static_update = u == 2;
	}
	for (auto [key, value] :
	     {std::pair<const char*, int*>{"compressed_passive_after", &compressed_passive_after},
	      {"compressed_batch", &compressed_batch}})
	{
		const long v = readInt(c, s, key, *value);
		if (v < 1 || v > 1000000)
			throw std::invalid_argument("[" + s + "] " + key + " = " + std::to_string(v) +
			                            ": must be in [1, 1000000]");
		*value = int(v);
	}
	innovation_gate = readNonNegative(c, s, "innovation_gate", innovation_gate);
	first_estimate_jacobians = readBool(c, s, "first_estimate_jacobians", first_estimate_jacobians);
	record_dropped = readBool(c, s, "record_dropped", record_dropped);
	const std::vector<std::string> methods{"gate",   "none",          "huber",
	                                       "cauchy", "gate_recovery", "jcbb"};
	outlier_method = methods[size_t(readChoice(c, s, "outlier_method", methods, 0))];
	robust_kernel_c = readPositive(c, s, "robust_kernel_c", robust_kernel_c);
	robust_iterations = int(readInt(c, s, "robust_iterations", robust_iterations));
	recovery_count = int(readInt(c, s, "recovery_count", recovery_count));
	recovery_inflation = readDouble(c, s, "recovery_inflation", recovery_inflation);
	recovery_min_updates = int(readInt(c, s, "recovery_min_updates", recovery_min_updates));
	odometry_bias.load(c, s);
	loadClassify(*this, c, s);
	if (feature_labels == "boxes") boxes = loadBoxTracker(c);
	try
	{
		validate();
	}
	catch (const std::invalid_argument& e)
	{
		// The section of the key the message starts with (e.g. "cv_gate = 2: ..." is
		// [ObjectModel]).
		const std::string what = e.what();
		const std::string home = sectionOfKey(what.substr(0, what.find_first_of(" :+")));
		throw std::invalid_argument("[" + (home.empty() || home == kCoreSection ? s : home) + "] " +
		                            what);
	}
}

namespace
{
/** prune_min_sightings = k, prune_window = W: both 0 (off), or 2 <= k <= W. */
void validatePruning(int k, int W)
{
	const std::string kw =
	    "prune_min_sightings = " + std::to_string(k) + ", prune_window = " + std::to_string(W);
	if (k < 0 || W < 0) throw std::invalid_argument(kw + ": both must be >= 0 (0 = off)");
	if (k == 0 && W == 0) return;
	if (W == 0)
		throw std::invalid_argument(kw + ": pruning needs a window of prune_window >= 1 steps");
	if (k == 0)
		throw std::invalid_argument(
		    kw + ": a window without prune_min_sightings prunes nothing (set k >= 2, or both 0)");
	if (k == 1)
		throw std::invalid_argument(kw +
		                            ": k = 1 prunes nothing (a landmark is read when it is "
		                            "added); use k >= 2, or 0 = off");
	if (k > W)
		throw std::invalid_argument(kw +
		                            ": k > W would prune every landmark (at most one reading "
		                            "per step); need prune_min_sightings <= prune_window");
}

/** fuse_landmarks_prob: 0 (off) or in (0, 1); the EKF's full state with feature_labels = ids. */
void validateFusion(const TModelOptions& o)
{
	const double p = o.fuse_landmarks_prob;
	if (p == 0) return;
	const std::string kw = "fuse_landmarks_prob = " + std::to_string(p);
	if (!(p > 0 && p < 1))
		throw std::invalid_argument(kw + ": must be a probability in (0, 1) (0 = off)");
	if (o.feature_labels != "ids")
		throw std::invalid_argument(
		    kw + ": implemented for feature_labels = ids only (feature_labels = " +
		    o.feature_labels + " keeps its own tracks per ID)");
	if (o.compressed_static_update)
		throw std::invalid_argument(kw +
		                            ": not implemented with static_update = compressed (the "
		                            "landmarks of the fused pair may be out of the working state)");
}
}  // namespace

bool TModelOptions::objectCentric() const
{
	const auto& models = estimator::objectMotionModels();
	return models.has(object_model) && models.caps(object_model).object_centric;
}

void TModelOptions::validate() const
{
	if (keep_last_poses < 1)
		throw std::invalid_argument("keep_last_poses = " + std::to_string(keep_last_poses) +
		                            ": must be >= 1");
	if (smoothing && keep_last_poses < 3)
		throw std::invalid_argument(
		    "keep_last_poses = " + std::to_string(keep_last_poses) +
		    ": smoothing needs the last 3 object poses (keep_last_poses >= 3)");
	if (!estimator::objectMotionModels().has(object_model))
	{
		std::string known;
		for (const auto& n : estimator::objectMotionModels().names())
			known += (known.empty() ? "" : ", ") + n;
		throw std::invalid_argument("object_model = " + object_model + ": must be one of " + known);
	}
	if (objectCentric() && smoothing)
		throw std::invalid_argument("object_model = " + object_model +
		                            ": the paper's smoothing (smoothing = true) "
		                            "is a different object model");
	if (!(cv_gate >= 0 && cv_gate < 1))
		throw std::invalid_argument("cv_gate = " + std::to_string(cv_gate) +
		                            ": must be a probability in [0, 1) (0 = no gate)");
	cv.validate();
	if (compressed_passive_after < 1)
		throw std::invalid_argument("compressed_passive_after = " +
		                            std::to_string(compressed_passive_after) + ": must be >= 1");
	if (compressed_batch < 1)
		throw std::invalid_argument("compressed_batch = " + std::to_string(compressed_batch) +
		                            ": must be >= 1");
	if (drop_static_after_unseen_steps < 0)
		throw std::invalid_argument(
		    "drop_static_after_unseen_steps = " + std::to_string(drop_static_after_unseen_steps) +
		    ": must be >= 0");
	validatePruning(prune_min_sightings, prune_window);
	if (drop_object_after_unseen_steps < 0)
		throw std::invalid_argument(
		    "drop_object_after_unseen_steps = " + std::to_string(drop_object_after_unseen_steps) +
		    ": must be >= 0 (0 = never)");
	if (drop_object_after_unseen_steps > 0 && feature_labels == "boxes")
		throw std::invalid_argument(
		    "drop_object_after_unseen_steps = " + std::to_string(drop_object_after_unseen_steps) +
		    ": implemented for feature_labels = ids and classify (with boxes the box tracker "
		    "deletes its tracks itself: [BoxTracker] max_age)");
	validateFusion(*this);
	if (!initial_pose.allFinite()) throw std::invalid_argument("initial_pose: not finite");
	if (!(innovation_gate >= 0 && innovation_gate < 1))
		throw std::invalid_argument("innovation_gate = " + std::to_string(innovation_gate) +
		                            ": must be a probability in [0, 1) (0 = no gate)");
	if (outlier_method != "gate" && !sparse_static_update)
		throw std::invalid_argument("outlier_method = " + outlier_method +
		                            ": needs static_update = sparse");
	if (outlier_method == "gate_recovery" && innovation_gate == 0)
		throw std::invalid_argument(
		    "outlier_method = gate_recovery: needs a gate (innovation_gate > 0)");
	if (outlier_method == "jcbb" && innovation_gate == 0)
		throw std::invalid_argument(
		    "outlier_method = jcbb: needs the confidence of its individual "
		    "and joint chi-square tests (innovation_gate in (0, 1))");
	if (feature_labels != "ids" && feature_labels != "classify" && feature_labels != "boxes")
		throw std::invalid_argument("feature_labels = " + feature_labels +
		                            ": must be ids, classify or boxes");
	classify.validate();
	if (feature_labels == "boxes") boxes.params.validate();
	if (feature_labels == "boxes" && compressed_static_update)
		throw std::invalid_argument(
		    "feature_labels = boxes: not implemented with static_update = compressed (the box "
		    "corners' IDs are given after the compressed state decides what to expand)");
	if (!(robust_kernel_c > 0) || robust_iterations < 1)
		throw std::invalid_argument("robust_kernel_c must be > 0 and robust_iterations >= 1");
	if (recovery_count < 1 || !(recovery_inflation > 1) || recovery_min_updates < 0)
		throw std::invalid_argument(
		    "recovery_count = " + std::to_string(recovery_count) +
		    ", recovery_inflation = " + std::to_string(recovery_inflation) +
		    ", recovery_min_updates = " + std::to_string(recovery_min_updates) +
		    ": need >= 1, > 1 and >= 0");
}

namespace
{
/** The section [ObjectModel] of the dump. */
void dumpObjectModel(std::ostream& out, const TModelOptions& o)
{
	using config::formatMatrix;
	out << "\n[" << kObjectModelSection << "]\n";
	out << "cv_dt                          = " << o.cv.dt << "\n";
	out << "cv_accel_psd                   = " << formatMatrix(o.cv.accel_psd.transpose()) << "\n";
	out << "cv_velocity_prior_std          = " << formatMatrix(o.cv.velocity_prior_std.transpose())
	    << "\n";
	out << "cv_gate                        = " << o.cv_gate << "\n";
	out << "cv_fallback_steps              = " << o.cv.fallback_steps << "\n";
	out << "cv_heading_inflation           = " << o.cv.heading_inflation << "\n";
	out << "ca_jerk_psd                    = " << formatMatrix(o.cv.jerk_psd.transpose()) << "\n";
	out << "ca_accel_prior_std             = " << formatMatrix(o.cv.accel_prior_std.transpose())
	    << "\n";
	out << "mm_switch_prob                 = " << o.cv.mm_switch_prob << "\n";
	out << "mm_manoeuvre_psd               = " << formatMatrix(o.cv.mm_manoeuvre_psd.transpose())
	    << "\n";
}

/** The section [Classify] of the dump. */
void dumpClassify(std::ostream& out, const estimator::TClassifyParams& classify)
{
	out << "\n[" << kClassifySection << "]\n";
	out << "classify_alpha                 = " << classify.alpha << "\n";
	out << "classify_beta                  = " << classify.beta << "\n";
	out << "classify_motion_std            = " << classify.motion_std << "\n";
	out << "classify_max_window            = " << classify.max_window << "\n";
	out << "classify_forget_steps          = " << classify.forget_steps << "\n";
	out << "classify_group_prob            = " << classify.group_prob << "\n";
	out << "classify_group_max_dist        = " << classify.group_max_dist << "\n";
	out << "classify_reclassify_count      = " << classify.reclassify_count << "\n";
	out << "classify_reclassify_gate       = " << classify.reclassify_gate << "\n";
	out << "classify_candidate_landmarks   = " << (classify.candidate_landmarks ? "true" : "false")
	    << "\n";
	out << "classify_reclassify            = " << (classify.surgery ? "surgery" : "restart")
	    << "\n";
	out << "classify_stop_count            = " << classify.stop_count << "\n";
	out << "classify_reuse_gap             = " << classify.reuse_gap << "\n";
	out << "classify_split_count           = " << classify.split_count << "\n";
	out << "classify_join                  = " << (classify.join ? "true" : "false") << "\n";
	out << "classify_use_hints             = " << (classify.use_hints ? "true" : "false") << "\n";
	const char* links[] = {"off", "hints", "all"};
	out << "classify_link                  = " << links[int(classify.link)] << "\n";
	out << "classify_link_gap              = " << classify.link_gap << "\n";
	out << "classify_merge_linked          = " << (classify.merge_linked ? "true" : "false")
	    << "\n";
	out << "classify_merge_live            = " << (classify.merge_live ? "true" : "false") << "\n";
	out << "classify_merge_live_window     = " << classify.merge_live_window << "\n";
	out << "classify_static_test           = "
	    << (classify.static_test == estimator::TClassifyParams::StaticTest::Map ? "map" : "robot")
	    << "\n";
	const estimator::TUnknownIdParams& a = classify.assoc;
	out << "classify_assoc_method          = " << a.method << "\n";
	out << "classify_assoc_metric          = " << a.metric << "\n";
	out << "classify_assoc_IC_chi2_thres   = " << a.IC_chi2_thres << "\n";
	out << "classify_assoc_IC_metric       = " << a.IC_metric << "\n";
	out << "classify_assoc_IC_ml_threshold = " << a.IC_ml_threshold << "\n";
	out << "classify_assoc_moving_gate     = " << a.moving_gate << "\n";
	out << "classify_assoc_max_step        = " << a.max_step << "\n";
}
}  // namespace

void TModelOptions::dumpToTextStream(std::ostream& out) const
{
	using config::formatMatrix;
	out << "\n----------- [CDynamicKFSLAM2D::TOptions] ------------\n\n";
	out << "measurement_model              = " << models::toString(measurement_model) << "\n";
	out << "Sigma_v                        = " << formatMatrix(Sigma_v) << "\n";
	out << "motion_noise                   = " << (motion_noise_from_action ? "action" : "config")
	    << "\n";
	out << "Sigma_w                        = " << formatMatrix(Sigma_w) << "\n";
	out << "initial_pose                   = " << formatMatrix(initial_pose.transpose()) << "\n";
	out << "Sigma_0                        = " << formatMatrix(Sigma_0) << "\n";
	out << "prior_gauge                    = " << (prior_gauge_anchor ? "anchor" : "prior") << "\n";
	out << "Sigma_xi                       = " << formatMatrix(Sigma_xi) << "\n";
	out << "smoothing                      = " << (smoothing ? "true" : "false") << "\n";
	out << "Sigma_s                        = " << formatMatrix(Sigma_s) << "\n";
	out << "object_model                   = " << object_model << "\n";
	out << "drop_time_t_features           = " << (drop_time_t_features ? "true" : "false") << "\n";
	out << "keep_last_poses                = " << keep_last_poses << "\n";
	out << "drop_static_after_unseen_steps = " << drop_static_after_unseen_steps << "\n";
	out << "prune_min_sightings            = " << prune_min_sightings << "\n";
	out << "prune_window                   = " << prune_window << "\n";
	out << "drop_object_after_unseen_steps = " << drop_object_after_unseen_steps << "\n";
	out << "fuse_landmarks_prob            = " << fuse_landmarks_prob << "\n";
	out << "skip_prediction_on_empty_map   = " << (skip_prediction_on_empty_map ? "true" : "false")
	    << "\n";
	out << "static_update                  = "
	    << (compressed_static_update ? "compressed"
	        : sparse_static_update   ? "sparse"
	                                 : "mrpt")
	    << "\n";
	out << "compressed_passive_after       = " << compressed_passive_after << "\n";
	out << "compressed_batch               = " << compressed_batch << "\n";
	out << "innovation_gate                = " << innovation_gate << "\n";
	out << "outlier_method                 = " << outlier_method << "\n";
	out << "robust_kernel_c                = " << robust_kernel_c << "\n";
	out << "robust_iterations              = " << robust_iterations << "\n";
	out << "recovery_count                 = " << recovery_count << "\n";
	out << "recovery_inflation             = " << recovery_inflation << "\n";
	out << "recovery_min_updates           = " << recovery_min_updates << "\n";
	out << "first_estimate_jacobians       = " << (first_estimate_jacobians ? "true" : "false")
	    << "\n";
	out << "record_dropped                 = " << (record_dropped ? "true" : "false") << "\n";
	out << "odometry_bias                  = " << odometry_bias.mode << "\n";
	out << "feature_labels                 = " << feature_labels << "\n";
	// The module sections after every key of the core section (the dump reads back as an INI).
	dumpObjectModel(out, *this);
	odometry_bias.dump(out);
	if (feature_labels == "ids") return;  // the classify_* keys only matter with classify
	dumpClassify(out, classify);
	if (feature_labels == "boxes")
	{
		out << "\n[BoxTracker]";  // its own section, as the modules' (the dump reads back)
		boxes.dumpToTextStream(out);
	}
}
TParseOptions TModelOptions::parseOptions() const
{
	return {measurement_model, motion_noise_from_action};
}

estimator::TDropOptions TModelOptions::dropOptions() const
{
	estimator::TDropOptions d;
	d.drop_time_t_features = drop_time_t_features;
	d.keep_last_poses = keep_last_poses;
	d.drop_static_after_unseen_steps = drop_static_after_unseen_steps;
	d.record_dropped = record_dropped;
	d.prune_min_sightings = prune_min_sightings;
	d.prune_window = prune_window;
	d.drop_object_after_unseen_steps = drop_object_after_unseen_steps;
	return d;
}

}  // namespace dynslam
