#include <dynslam/apps/CTrackerBaselineBackend.h>
#include <dynslam/apps/app_main.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/slam_services.h>
#include <dynslam/common/model_keys.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/framework/TBackendOptions.h>
#include <dynslam/framework/backend_factory.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
/** dynslam-compare's filters dynamic_cv / dynamic_ctrv / dynamic_smoothing: the [DynamicKFSLAM]
 * filter with another object model. cv and ctrv need cv_dt in [ObjectModel] (no silent default for
 * the step length); paper_smoothing keeps at least the 3 poses it needs. */
void overrideObjectModel(CDynamicKFSLAM2D& f, const mrpt::config::CConfigFileBase& ini,
                         const std::string& model)
{
	const estimator::TObjectMotionCaps& caps = estimator::objectMotionModels().caps(model);
	if (caps.object_centric && !ini.keyExists(kObjectModelSection, "cv_dt"))
		throw std::invalid_argument("[ObjectModel] cv_dt: required by the filter dynamic_" + model +
		                            " (seconds per step)");
	if (caps.smoothing && !ini.keyExists("DynamicKFSLAM", "Sigma_s"))
		throw std::invalid_argument(
		    "[DynamicKFSLAM] Sigma_s: required by the filter dynamic_smoothing");
	f.options.object_model = model;
	f.options.smoothing = caps.smoothing;
	if (f.options.smoothing) f.options.keep_last_poses = std::max(3, f.options.keep_last_poses);
	f.options.validate();
	f.reset();
}
}  // namespace

const std::vector<std::string>& backendKinds()
{
	static const std::vector<std::string> k = []
	{
		std::vector<std::string> v{"ekf", "static_all", "static_landmarks_only", "odometry",
		                           "tracker_baseline"};
		for (const auto& f : framework::backendKinds()) v.push_back(f);
		return v;
	}();
	return k;
}

std::unique_ptr<ISlamBackend> makeBackend(const std::string& kind,
                                          const mrpt::config::CConfigFileBase& ini,
                                          std::ostream* optionsDump)
{
	if (kind == "ekf" || kind == "dynamic" || kind == "dynamic_cv" || kind == "dynamic_ctrv" ||
	    kind == "dynamic_mm" || kind == "dynamic_smoothing" || kind == "dynamic_classified")
	{
		auto f = std::make_unique<CDynamicKFSLAM2D>();
		f->loadOptions(ini, "DynamicKFSLAM");
		if (kind == "dynamic_cv" || kind == "dynamic_ctrv" || kind == "dynamic_mm")
			overrideObjectModel(*f, ini, kind.substr(8));
		else if (kind == "dynamic_smoothing")
			overrideObjectModel(*f, ini, "paper_smoothing");
		if (kind == "dynamic_classified")  // issue 12: the same filter, no ID oracle
		{
			f->options.feature_labels = "classify";
			f->options.validate();
			f->reset();
		}
		if (optionsDump)
		{
			*optionsDump
			    << "# [DynamicKFSLAM] and its modules' sections (CDynamicKFSLAM2D::TOptions)";
			f->options.dumpToTextStream(*optionsDump);
			*optionsDump << "\n# [DynamicKFSLAM_KalmanFilter] (mrpt::bayes::TKF_options)";
			f->KF_options.dumpToTextStream(*optionsDump);
		}
		return f;
	}
	if (kind == "static_all" || kind == "static_landmarks_only")
		return slamStaticBaseline(kind, ini, optionsDump);
	if (kind == "odometry" || kind == "tracker_baseline")  // issue 31: dead reckoning, the peer
	{
		std::unique_ptr<CDeadReckoningBackend> b;
		if (kind == "odometry")
			b = std::make_unique<CDeadReckoningBackend>();
		else
			b = std::make_unique<CTrackerBaselineBackend>();
		b->loadOptions(ini);
		if (optionsDump) b->dumpOptions(*optionsDump);
		return b;
	}
	const auto& fk = framework::backendKinds();
	if (std::find(fk.begin(), fk.end(), kind) != fk.end())
	{
		// The optimization framework's back-ends: [Backend] (window, iterations, ...) and the
		// model from its model_section (default [DynamicKFSLAM]).
		framework::TBackendOptions o = framework::defaultBackendOptions(kind);
		o.loadFromConfigFile(ini, "Backend");
		if (o.backend != kind)
			throw std::invalid_argument("[Backend] backend = " + o.backend +
			                            " differs from the requested back-end " + kind);
		if (optionsDump)
		{
			*optionsDump << "# [Backend] and its model section (framework::TBackendOptions)";
			o.dumpToTextStream(*optionsDump);
		}
		return framework::makeBackend(o);
	}
	std::string known;
	for (const auto& k : backendKinds()) known += (known.empty() ? "" : " | ") + k;
	throw std::invalid_argument("unknown back-end '" + kind + "' (known: " + known + ")");
}

void collectFinalEstimates(const ISlamBackend& backend, eval::TRunEstimates& est)
{
	est.landmarks.clear();
	est.landmarks_cov.resize(0, 0);
	est.object_features.clear();
	est.object_poses.clear();

	const auto lms = allStaticLandmarks(backend);
	bool allInState = true;
	for (const auto& l : lms)
	{
		eval::TLandmarkEstimate e;
		e.id = l.id;
		e.mean = l.mean;
		e.cov = l.cov;
		est.landmarks.push_back(e);
		allInState = allInState && l.in_state;
	}

	est.odometry_bias.resize(0);
	if (const auto* dyn = dynamic_cast<const CDynamicKFSLAM2D*>(&backend))
		if (const auto b = dyn->getOdometryBias()) est.odometry_bias = b->first;

	// Joint landmark covariance, in the order of est.landmarks.
	if (const auto* dyn = dynamic_cast<const CDynamicKFSLAM2D*>(&backend); dyn && allInState)
	{
		std::vector<size_t> idx;
		const auto& slots = dyn->getSlots();
		for (size_t s = 0; s < slots.size(); ++s)
			if (slots[s].kind == SlotKind::StaticLandmark)
			{
				if (idx.size() / 2 >= lms.size() || slots[s].id != lms[idx.size() / 2].id) break;
				idx.push_back(3 + 2 * s);
				idx.push_back(4 + 2 * s);
			}
		if (idx.size() == 2 * lms.size())
		{
			const Eigen::MatrixXd P = dyn->reportedCov();  // prior_gauge = anchor: + N Sigma_0 N^T
			est.landmarks_cov.resize(Eigen::Index(idx.size()), Eigen::Index(idx.size()));
			for (size_t i = 0; i < idx.size(); ++i)
				for (size_t j = 0; j < idx.size(); ++j) est.landmarks_cov(i, j) = P(idx[i], idx[j]);
		}
	}
	else if (Eigen::MatrixXd C; slamStaticBaselineJointCov(backend, C))
	{
		if (C.rows() == Eigen::Index(2 * lms.size())) est.landmarks_cov = std::move(C);
	}

	for (const auto& f : backend.getObjectFeatures())
	{
		if (!f.at_time0) continue;
		eval::TObjectFeatureEstimate e;
		e.object = f.object;
		e.feature = f.feature;
		e.mean = f.mean;
		e.cov = f.cov;
		est.object_features.push_back(e);
	}
	for (const auto& [obj, track] : backend.getObjectTracks())
		for (const auto& p : track.poses)
		{
			eval::TObjectPoseEstimate e;
			e.object = obj;
			e.step = p.step;
			e.mean = p.mean;
			e.cov = p.cov;
			e.velocity = p.velocity;
			e.velocity_cov = p.velocity_cov;
			e.mode_probabilities = p.mode_probabilities;
			est.object_poses.push_back(e);
		}
	est.object_mode_names = backend.objectModeNames();
}

TFilterRun runFilter(ISlamBackend& backend,
                     const std::vector<mrpt::obs::CActionCollection::Ptr>& actions,
                     const std::vector<mrpt::obs::CSensoryFrame::Ptr>& frames,
                     const std::function<void(size_t, size_t)>& progress,
                     const std::function<void(size_t, double)>& stepTime)
{
	if (actions.size() != frames.size())
		throw std::invalid_argument("runFilter: different numbers of actions and sensory frames");
	using Clock = std::chrono::steady_clock;
	TFilterRun r;
	r.name = backend.name();
	const size_t n = actions.size();
	r.est.ego.reserve(n);
	r.est.nis.assign(n, 0.0);
	r.est.nis_dof.assign(n, 0);
	r.stamps.assign(n, std::numeric_limits<double>::quiet_NaN());
	double ns = 0;
	for (size_t k = 0; k < n; ++k)
	{
		const auto t0 = Clock::now();
		try
		{
			backend.processActionObservation(actions[k], frames[k]);
		}
		catch (const std::exception& e)
		{
			throw std::runtime_error(r.name + ": step " + std::to_string(k) + ": " +
			                         oneLineReason(e));
		}
		const double stepNs =
		    double(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count());
		ns += stepNs;
		if (stepTime) stepTime(k, stepNs * 1e-6);

		const auto pose = backend.getEgoPose();
		eval::TEgoEstimate e;
		e.step = int(k);
		e.mean = Eigen::Vector3d(pose.mean.x(), pose.mean.y(), pose.mean.phi());
		e.cov = pose.cov.asEigen();
		r.est.ego.push_back(e);
		const TStepReport& rep = backend.getLastStepReport();
		r.est.nis[k] = rep.nis_static;
		r.est.nis_dof[k] = int(rep.nis_static_dof);
		if (frames[k])
			if (auto o = frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>())
				r.stamps[k] = mrpt::Clock::toDouble(o->timestamp);
		if (progress) progress(k + 1, n);
	}
	r.steps = n;
	r.total_ms = ns * 1e-6;
	r.est.ms_per_step = n ? r.total_ms / double(n) : 0.0;
	collectFinalEstimates(backend, r.est);
	return r;
}
}  // namespace dynslam::apps
