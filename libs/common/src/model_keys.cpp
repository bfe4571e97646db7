/** The descriptor table of the model's sections and the generated key reference (model_keys.h). */
#include <dynslam/common/model_keys.h>

#include <cctype>
#include <ostream>

namespace dynslam
{
namespace
{
constexpr const char* kModel = "Measurement, motion and prior";
constexpr const char* kObjects = "Objects (the paper's formulation)";
constexpr const char* kMotion = "Object motion models (object_model = cv, ctrv, ca, mm)";
constexpr const char* kUpdate = "Static update and outliers";
constexpr const char* kBias = "Odometry bias (odometry_bias = rate, rate_scale)";
constexpr const char* kClassify = "Classification (feature_labels = classify)";
constexpr const char* kProb = "probability in (0, 1)";
constexpr const char* kPrune = "Pruning (long runs with clutter)";

/** The table (a variable, not a function: one row per key). */
const std::vector<TKeyInfo> kKeys{
    {"measurement_model", "cartesian | range_bearing", "required", "-",
     "cartesian: Sigma_v on the sensor-frame point (paper); range_bearing: MRPT's", kModel},
    {"Sigma_v", "2x2 covariance", "required", "m^2 or [m^2, rad^2]",
     "measurement noise in the model's space; `[a b]` is the diagonal", kModel},
    {"motion_noise", "action | config", "action", "-",
     "odometry noise: the action's covariance (rotated as MRPT does) or Sigma_w", kModel},
    {"Sigma_w", "3x3 covariance", "[0.0001 0 0; 0 0.0001 0; 0 0 0.0001]", "[m^2, m^2, rad^2]",
     "odometry increment noise; required with motion_noise = config", kModel},
    {"initial_pose", "vector of 3", "[0 0 0]", "[m, m, rad]", "mean of x_0", kModel},
    {"Sigma_0", "3x3 covariance (PSD)", "[0 0 0; 0 0 0; 0 0 0]", "[m^2, m^2, rad^2]",
     "covariance of x_0", kModel},
    {"prior_gauge", "prior | anchor", "prior", "-",
     "anchor: the filter runs with x_0 as the gauge, Sigma_0 enters only the reported "
     "covariances (doc/state-layout.md); EKF only",
     kModel},
    {"Sigma_xi", "2x2 covariance", "[0.1 0; 0 0.1]", "m^2",
     "per-feature residual covariance of the object-pose map (Alg. 4)", kObjects},
    {"smoothing", "bool", "false", "-", "Alg. 6 (the paper's smoothing)", kObjects},
    {"Sigma_s", "3x3 covariance", "[0.01 0 0; 0 0.01 0; 0 0 0.01]", "[m^2, m^2, rad^2]",
     "smoothing covariance; required with smoothing = true", kObjects},
    {"drop_time_t_features", "bool", "true", "-", "drop f_t after the pose augmentation", kObjects},
    {"keep_last_poses", "int >= 1", "1", "poses",
     "object poses kept per object (>= 3 with smoothing)", kObjects},
    {"drop_static_after_unseen_steps", "int >= 0", "0", "steps",
     "drop static landmarks unseen this long (0: never)", kObjects},
    {"drop_object_after_unseen_steps", "int >= 0", "0", "steps",
     "drop an object without readings this long, its track recorded per record_dropped "
     "(0: never); EKF with feature_labels = ids or classify",
     kObjects},
    {"skip_prediction_on_empty_map", "bool", "false", "-",
     "no prediction while the map is empty (MRPT's CRangeBearingKFSLAM2D)", kObjects},
    {"object_model", "paper | paper_smoothing | cv | ctrv | ca | mm", "paper", "-",
     "how objects move: the paper's formulation, or a velocity in the state", kMotion},
    {"cv_dt", "real > 0", "0.5", "s", "seconds per step; required with cv, ctrv, ca and mm",
     kMotion, kObjectModelSection},
    {"cv_accel_psd", "vector of 3, >= 0", "[0.1 0.1 0.01]", "[m^2/s^3, m^2/s^3, rad^2/s^3]",
     "white-acceleration spectral densities", kMotion, kObjectModelSection},
    {"cv_velocity_prior_std", "vector of 3, > 0", "[1 1 0.1]", "[m/s, m/s, rad/s]",
     "initialisation noise of an object's velocity", kMotion, kObjectModelSection},
    {"cv_gate", "probability in [0, 1)", "0", "-", "chi-square gate on object readings (0: none)",
     kMotion, kObjectModelSection},
    {"cv_fallback_steps", "int >= 0", "0", "steps",
     "an object gated out this many steps in a row falls back to the paper's formulation "
     "(0: off); EKF only",
     kMotion, kObjectModelSection},
    {"cv_heading_inflation", "real >= 0", "0", "-",
     "object readings' noise Sigma_v + c P_thth h h^T (0: off); EKF only", kMotion,
     kObjectModelSection},
    {"ca_jerk_psd", "vector of 3, >= 0", "[0.01 0.01 0.001]", "[m^2/s^5, m^2/s^5, rad^2/s^5]",
     "ca: white-jerk spectral densities (its process noise; > 0 in the framework)", kMotion,
     kObjectModelSection},
    {"ca_accel_prior_std", "vector of 3, > 0", "[0.5 0.5 0.05]", "[m/s^2, m/s^2, rad/s^2]",
     "ca: initialisation noise of an object's acceleration (mean 0)", kMotion, kObjectModelSection},
    {"mm_switch_prob", "probability in (0, 1)", "0.01", "-",
     "mm: probability of leaving a mode per step (Markov switching, spread evenly); EKF and alg1",
     kMotion, kObjectModelSection},
    {"mm_manoeuvre_psd", "vector of 3, > 0", "[16 16 0.1]", "[m^2/s^3, m^2/s^3, rad^2/s^3]",
     "mm: white-acceleration spectral densities of the manoeuvre mode", kMotion,
     kObjectModelSection},
    {"static_update", "mrpt | sparse | compressed", "sparse", "-",
     "the static update engine (compressed: the exact compressed EKF)", kUpdate},
    {"compressed_passive_after", "int in [1, 1000000]", "3", "steps",
     "compressed: a landmark unseen this long becomes passive", kUpdate},
    {"compressed_batch", "int in [1, 1000000]", "8", "landmarks",
     "compressed: landmarks made passive only when this many are due", kUpdate},
    {"innovation_gate", "probability in [0, 1)", "0", "-",
     "chi-square gate on static readings (0: none)", kUpdate},
    {"outlier_method", "gate | none | huber | cauchy | gate_recovery | jcbb", "gate", "-",
     "static outlier handling; all but gate need static_update = sparse", kUpdate},
    {"robust_kernel_c", "real > 0", "2", "Mahalanobis units", "huber / cauchy: the kernel's width",
     kUpdate},
    {"robust_iterations", "int >= 1", "5", "-", "huber / cauchy: IRLS updates at most", kUpdate},
    {"recovery_count", "int >= 1", "5", "readings",
     "gate_recovery: consecutive rejections of a landmark before the inflation", kUpdate},
    {"recovery_inflation", "real > 1", "4", "-", "gate_recovery: factor on the ego covariance",
     kUpdate},
    {"recovery_min_updates", "int >= 0", "3", "readings",
     "gate_recovery: accepted readings a landmark needs first", kUpdate},
    {"first_estimate_jacobians", "bool", "false", "-",
     "first-estimate Jacobians (Huang et al. 2008)", kUpdate},
    {"record_dropped", "bool", "true", "-", "keep the last estimate of dropped poses and landmarks",
     kUpdate},
    {"odometry_bias", "none | rate | rate_scale", "none", "-",
     "online odometry bias: turn rate, and the translation scale", kBias},
    {"odometry_dt", "real > 0", "required", "s",
     "step duration when the actions' timestamps give none", kBias, kOdometryBiasSection},
    {"bias_rate_std0", "real > 0", "required", "rad/s", "prior std of the turn-rate bias", kBias,
     kOdometryBiasSection},
    {"bias_rate_rw", "real >= 0", "required", "rad/s/sqrt(s)", "random walk of the turn-rate bias",
     kBias, kOdometryBiasSection},
    {"bias_scale_std0", "real > 0", "required", "-", "rate_scale: prior std of the scale error",
     kBias, kOdometryBiasSection},
    {"bias_scale_rw", "real >= 0", "required", "1/sqrt(s)",
     "rate_scale: random walk of the scale error", kBias, kOdometryBiasSection},
    {"feature_labels", "ids | classify | boxes", "ids", "-",
     "ids: the ID ranges say what a reading is; classify: anonymous tracks classified "
     "online; boxes: detector boxes without IDs, tracked ([BoxTracker]) then classified "
     "(EKF only)",
     kClassify},
    {"classify_alpha", kProb, "0.01", "-", "P(decide moving | static) of the SPRT", kClassify,
     kClassifySection},
    {"classify_beta", kProb, "0.01", "-", "P(decide static | moving); alpha + beta < 1", kClassify,
     kClassifySection},
    {"classify_motion_std", "real > 0", "0.5", "m per step",
     "the moving hypothesis: a random walk of this std", kClassify, kClassifySection},
    {"classify_max_window", "int >= 2", "10", "sightings", "sightings before a forced decision",
     kClassify, kClassifySection},
    {"classify_forget_steps", "int >= 1", "20", "steps",
     "an unseen candidate is forgotten after this many steps", kClassify, kClassifySection},
    {"classify_group_prob", kProb, "0.99", "-",
     "rigid-distance chi-square probability of the grouping", kClassify, kClassifySection},
    {"classify_group_max_dist", "real > 0", "6", "m",
     "features of one object at most this far apart", kClassify, kClassifySection},
    {"classify_reclassify_count", "int >= 0", "3", "readings",
     "consecutive inconsistent readings that turn a static track moving (0: never)", kClassify,
     kClassifySection},
    {"classify_reclassify_gate", kProb, "0.999", "-",
     "chi-square probability of a static track's gate", kClassify, kClassifySection},
    {"classify_candidate_landmarks", "bool", "true", "-",
     "a candidate's first reading initialises an isolated landmark", kClassify, kClassifySection},
    {"classify_reclassify", "surgery | restart", "surgery", "-",
     "a reclassified landmark becomes its object's f_0, or is dropped", kClassify,
     kClassifySection},
    {"classify_stop_count", "int >= 0", "0", "readings",
     "consistent readings that turn a moving track static (0: never)", kClassify, kClassifySection},
    {"classify_reuse_gap", "int >= 0", "0", "steps",
     "a track unseen this long and inconsistent restarts under a fresh ID (0: never)", kClassify,
     kClassifySection},
    {"classify_split_count", "int >= 0", "3", "readings",
     "inconsistent readings that split a track off its object (0: never)", kClassify,
     kClassifySection},
    {"classify_join", "bool", "true", "-", "a moving track may join an object of an earlier step",
     kClassify, kClassifySection},
    {"classify_use_hints", "bool", "false", "-",
     "detection groups (boxes) are evidence for the grouping", kClassify, kClassifySection},
    {"classify_link", "off | hints | all", "hints", "-",
     "which new objects may continue an object lost after a break", kClassify, kClassifySection},
    {"classify_link_gap", "int >= 1", "80", "steps", "the longest break a link may span", kClassify,
     kClassifySection},
    {"classify_merge_linked", "bool", "false", "-",
     "a link also merges the new object into the lost one (cv, ctrv)", kClassify, kClassifySection},
    {"classify_merge_live", "bool", "false", "-",
     "two live objects moving as one rigid body are merged", kClassify, kClassifySection},
    {"classify_merge_live_window", "int >= 0", "0", "steps",
     "increments per live-merge decision (0: 5 with cv / ctrv, 20 with paper)", kClassify,
     kClassifySection},
    {"classify_static_test", "robot | map", "robot", "-",
     "a static track's reading tested in the robot frame or against the map", kClassify,
     kClassifySection},
    {"classify_assoc_method", "assocNN | assocJCBB", "assocNN", "-",
     "ID -1, static stage (MRPT's data_assoc_method)", kClassify, kClassifySection},
    {"classify_assoc_metric", "metricMaha | metricML", "metricMaha", "-",
     "MRPT's data_assoc_metric", kClassify, kClassifySection},
    {"classify_assoc_IC_chi2_thres", kProb, "0.99", "-",
     "individual compatibility (MRPT's data_assoc_IC_chi2_thres)", kClassify, kClassifySection},
    {"classify_assoc_IC_metric", "metricMaha | metricML", "metricMaha", "-",
     "MRPT's data_assoc_IC_metric", kClassify, kClassifySection},
    {"classify_assoc_IC_ml_threshold", "real", "0", "-", "MRPT's data_assoc_IC_ml_threshold",
     kClassify, kClassifySection},
    {"classify_assoc_moving_gate", kProb, "0.99", "-",
     "ID -1, moving stage: chi-square probability (2 dof)", kClassify, kClassifySection},
    {"classify_assoc_max_step", "real >= 0", "0", "m per step",
     "ID -1, second sightings of candidates (0: off)", kClassify, kClassifySection},
    {"prune_min_sightings", "0, or int in [2, prune_window]", "0", "readings",
     "a static landmark read in fewer of its first prune_window steps is removed (clutter; "
     "recorded per record_dropped; 0: off); EKF and alg1",
     kPrune},
    {"prune_window", "int >= 0; >= 1 with prune_min_sightings", "0", "steps",
     "the steps from a static landmark's first reading on in which it is counted (0: off)", kPrune},
    {"fuse_landmarks_prob", "0, or probability in (0, 1)", "0", "-",
     "two static landmarks whose difference passes the chi-square test (2 dof) at this "
     "probability, each the other's only compatible neighbour and never read in one step, are "
     "fused, the newer ID read as the older one (re-identified landmarks after track breaks; "
     "0: off); EKF with feature_labels = ids, not compressed",
     kPrune}};
}  // namespace

const std::vector<std::string>& moduleSections()
{
	static const std::vector<std::string> s{kObjectModelSection, kOdometryBiasSection,
	                                        kClassifySection};
	return s;
}

const std::vector<TKeyInfo>& modelKeys() { return kKeys; }

std::vector<std::string> modelKeyNames()
{
	std::vector<std::string> n;
	for (const TKeyInfo& k : modelKeys()) n.push_back(k.key);
	return n;
}

std::vector<std::string> sectionKeyNames(const std::string& section)
{
	std::vector<std::string> n;
	for (const TKeyInfo& k : modelKeys())
		if (k.section == section) n.push_back(k.key);
	return n;
}

std::string sectionOfKey(const std::string& key)
{
	const auto lower = [](std::string x)
	{
		for (char& ch : x) ch = char(std::tolower(static_cast<unsigned char>(ch)));
		return x;
	};
	for (const TKeyInfo& k : modelKeys())
		if (lower(k.key) == lower(key)) return k.section;
	return "";
}

namespace
{
std::string profilesSetting(const TKeyInfo& key, const std::vector<TProfileKeys>& profiles)
{
	std::string s;
	for (const TProfileKeys& p : profiles)
		for (const TProfileKeys::TSetting& k : p.keys)
			if (k.section == key.section && k.key == key.key)
				s += (s.empty() ? "" : "; ") + p.name + " `" + k.value + "`";
	return s.empty() ? "-" : s;
}

/** `|` as `\|` (a markdown table's cell). */
std::string escapeBars(std::string s)
{
	for (size_t p = s.find('|'); p != std::string::npos; p = s.find('|', p + 2))
		s.replace(p, 1, "\\|");
	return s;
}

/** The tables of one section's keys, one per capability. */
void writeSection(std::ostream& out, const std::string& section,
                  const std::vector<TProfileKeys>& profiles)
{
	const size_t n = sectionKeyNames(section).size();
	out << "\n### `[" << section << "]`: " << n << " keys\n";
	std::string group;
	for (const TKeyInfo& k : modelKeys())
	{
		if (k.section != section) continue;
		if (k.capability != group)
		{
			group = k.capability;
			out << "\n#### " << group << "\n\n"
			    << "| key | type | default | unit | profiles | what |\n"
			    << "|---|---|---|---|---|---|\n";
		}
		out << "| `" << k.key << "` | " << escapeBars(k.type) << " | `" << k.def << "` | " << k.unit
		    << " | " << profilesSetting(k, profiles) << " | " << escapeBars(k.what) << " |\n";
	}
}
}  // namespace

void writeKeyReference(std::ostream& out, const std::vector<TProfileKeys>& profiles)
{
	writeSection(out, kCoreSection, profiles);
	for (const std::string& s : moduleSections()) writeSection(out, s, profiles);
	out << "\n"
	    << modelKeys().size() << " keys in " << 1 + moduleSections().size() << " sections.\n";
}
}  // namespace dynslam
