#include <dynslam/core/landmark_ids.h>
#include <dynslam/mrclam/import.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dynslam::mrclam
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::Vector2d toFrame(const Eigen::Vector3d& origin, const Eigen::Vector2d& p)
{
	const Eigen::Vector3d r = relativeSE2(origin, Eigen::Vector3d(p.x(), p.y(), 0));
	return r.head<2>();
}

/** [lo, hi] where steps may lie. */
void timeWindow(const TDataset& d, const std::map<int, CTrajectoryInterpolator>& gt, bool clip,
                double& lo, double& hi)
{
	const auto& ego = gt.at(d.ego);
	lo = ego.tBegin();
	hi = ego.tEnd();
	if (clip)
		for (const auto& [r, traj] : gt)
		{
			lo = std::max(lo, traj.tBegin());
			hi = std::min(hi, traj.tEnd());
		}
}
}  // namespace

TImportOptions::TImportOptions()
{
	auto& n = odometry_noise;
	n.std_xy_min = 0.000319;
	n.var_xy_per_m = 0.000213;
	n.var_xy_per_rad = 0.000153;
	n.std_phi_min = 0.00136;
	n.var_phi_per_m = 0.00171;
	n.var_phi_per_rad = 0.00705;
	n.tau_xy = 15;
	n.tau_phi = 1;
}

size_t TImportSummary::landmarkMeasurements() const
{
	size_t n = 0;
	for (const auto& [s, c] : per_subject)
		if (isLandmarkSubject(s)) n += c;
	return n;
}

size_t TImportSummary::robotMeasurements() const
{
	size_t n = 0;
	for (const auto& [s, c] : per_subject)
		if (isRobotSubject(s)) n += c;
	return n;
}

std::string TImportSummary::toText() const
{
	std::ostringstream o;
	o.precision(15);
	o << "dataset: " << dataset << "\n"
	  << "ego robot: " << ego << "\n"
	  << "steps: " << steps << "\n"
	  << "first step time [s]: " << t_first << "\n"
	  << "last step time [s]: " << t_last << "\n";
	o.precision(6);
	o << "duration [s]: " << duration() << "\n"
	  << "measurement rows: " << rows << "\n"
	  << "kept: " << kept << " (landmarks " << landmarkMeasurements() << ", robots "
	  << robotMeasurements() << ")\n"
	  << "dropped spurious barcodes: " << spurious;
	if (!spurious_per_barcode.empty())
	{
		o << " (";
		bool first = true;
		for (const auto& [b, c] : spurious_per_barcode)
		{
			o << (first ? "" : ", ") << "barcode " << b << ": " << c;
			first = false;
		}
		o << ")";
	}
	o << "\n"
	  << "dropped own barcode: " << own_barcode << "\n"
	  << "dropped duplicates in a step: " << duplicates << "\n"
	  << "dropped outside the time window: " << outside_window << "\n"
	  << "max kept range [m]: " << max_range_seen << "\n"
	  << "largest Vicon gap in the window [s]: " << max_gt_gap << "\n";
	o.precision(10);
	o << "world origin (ego Vicon pose at step 0) x y theta: " << origin.x() << " " << origin.y()
	  << " " << origin.z() << "\n"
	  << "measurements per subject:\n";
	for (const auto& [s, c] : per_subject)
		o << "  subject " << s << (isRobotSubject(s) ? " (robot)" : " (landmark)") << ": " << c
		  << "\n";
	if (!anonymous_ids.empty())
	{
		o << "anonymous IDs (seed " << anonymous_seed << "), subject -> ID:";
		for (const auto& [s, id] : anonymous_ids) o << " " << s << "->" << id;
		o << "\n";
	}
	return o.str();
}

namespace
{
/** Filter id of an accepted subject; throws when its ground truth is missing. */
int32_t subjectFilterId(const TDataset& d, const std::map<int, CTrajectoryInterpolator>& gt,
                        const std::string& measFile, int line, int subject)
{
	if (isLandmarkSubject(subject))
	{
		if (!d.landmarks.count(subject))
			throw std::runtime_error(measFile + ":" + std::to_string(line) + ": landmark subject " +
			                         std::to_string(subject) +
			                         " has no entry in Landmark_Groundtruth.dat");
		return subject;
	}
	if (!gt.count(subject))
		throw std::runtime_error(measFile + ":" + std::to_string(line) + ": robot subject " +
		                         std::to_string(subject) + " has no ground truth");
	return ids::objectFeatureId(subject, 0);
}

/** Groups the measurements inside [lo, hi] into steps, counting the dropped ones in sum. */
std::vector<TStep> groupSteps(const TDataset& d, const std::map<int, CTrajectoryInterpolator>& gt,
                              const TImportOptions& opts, double lo, double hi,
                              const std::string& measFile, TImportSummary& sum)
{
	std::vector<TStep> steps;
	double groupStart = -std::numeric_limits<double>::infinity();
	double tFirst = kNaN;
	TStep cur;
	bool open = false;
	auto closeGroup = [&]()
	{
		if (open && !cur.meas.empty()) steps.push_back(cur);
		open = false;
	};
	for (const auto& m : d.measurements)
	{
		double hiNow = hi;
		if (opts.duration > 0 && !std::isnan(tFirst)) hiNow = std::min(hi, tFirst + opts.duration);
		if (m.t < lo || m.t > hiNow)
		{
			sum.outside_window++;
			continue;
		}
		if (!open || m.t - groupStart > opts.group_window)
		{
			closeGroup();
			cur = TStep();
			cur.t = groupStart = m.t;
			open = true;
		}
		const auto itB = d.barcodeToSubject.find(m.barcode);
		if (itB == d.barcodeToSubject.end())
		{
			sum.spurious++;
			sum.spurious_per_barcode[m.barcode]++;
			continue;
		}
		const int subject = itB->second;
		if (subject == d.ego)
		{
			sum.own_barcode++;
			continue;
		}
		if (std::any_of(cur.meas.begin(), cur.meas.end(),
		                [&](const TStepMeasurement& x) { return x.subject == subject; }))
		{
			sum.duplicates++;
			continue;
		}
		const int32_t id = subjectFilterId(d, gt, measFile, m.line, subject);
		if (std::isnan(tFirst)) tFirst = cur.t;
		cur.meas.push_back({subject, id, m.t, m.range, m.bearing, m.line});
		sum.kept++;
		sum.per_subject[subject]++;
		sum.max_range_seen = std::max(sum.max_range_seen, m.range);
	}
	closeGroup();
	return steps;
}

/** Sets each step's odometry increment (from the previous step) and its covariance. */
void addOdometry(const TDataset& d, const TImportOptions& opts, std::vector<TStep>& steps)
{
	const COdometryIntegrator odo(d.odometry, opts.odometry_delay, opts.odometry_scale_v,
	                              opts.odometry_scale_w);
	for (size_t k = 1; k < steps.size(); k++)
	{
		steps[k].increment = odo.integrate(steps[k - 1].t, steps[k].t);
		steps[k].cov = opts.odometry_noise.covariance(steps[k].increment);
	}
}

/** Placeholder for the ego and for robots without ground truth: never observed, NaN positions. */
io::TObjectGroundTruth placeholderObject(int r, size_t K)
{
	io::TObjectGroundTruth o;
	o.object = r;
	o.num_features = 1;
	o.features.assign(K, Eigen::Matrix2Xd::Constant(2, 1, kNaN));
	o.pose.assign(K, Eigen::Vector3d::Constant(kNaN));
	o.visible.assign(K, 0);
	return o;
}

/** Ground truth of robot r in the world frame at origin: its position as a one-feature object,
 * its pose the displacement since its first observation. */
io::TObjectGroundTruth robotObject(int r, const CTrajectoryInterpolator& traj,
                                   const std::vector<TStep>& steps, const Eigen::Vector3d& origin)
{
	const size_t K = steps.size();
	io::TObjectGroundTruth o;
	o.object = r;
	o.num_features = 1;
	for (size_t k = 0; k < K; k++)
	{
		const bool vis = std::any_of(steps[k].meas.begin(), steps[k].meas.end(),
		                             [&](const TStepMeasurement& x) { return x.subject == r; });
		o.visible.push_back(vis ? 1 : 0);
		if (vis && o.first_step < 0) o.first_step = static_cast<int>(k);
		Eigen::Matrix2Xd f(2, 1);
		if (traj.covers(steps[k].t))
			f.col(0) = toFrame(origin, traj.at(steps[k].t).head<2>());
		else
			f.setConstant(kNaN);  // only without clip_to_ground_truth
		o.features.push_back(f);
	}
	for (size_t k = 0; k < K; k++)
	{
		if (o.first_step >= 0 && static_cast<int>(k) >= o.first_step)
		{
			const Eigen::Vector2d dp = o.features[k].col(0) - o.features[o.first_step].col(0);
			o.pose.emplace_back(dp.x(), dp.y(), 0.0);
		}
		else
			o.pose.emplace_back(kNaN, kNaN, kNaN);
	}
	return o;
}

/** Ground truth of the steps in the frame of origin (the ego's pose at step 0). */
io::TGroundTruth groundTruthInFrame(const TDataset& d,
                                    const std::map<int, CTrajectoryInterpolator>& gt,
                                    const std::vector<TStep>& steps, const Eigen::Vector3d& origin)
{
	io::TGroundTruth g;
	for (const auto& s : steps)
	{
		g.t.push_back(s.t);
		g.ego.push_back(relativeSE2(origin, gt.at(d.ego).at(s.t)));
	}
	for (const auto& [s, p] : d.landmarks) g.landmarks[s] = toFrame(origin, p);
	// io::TGroundTruth stores object i at index i, so objects 0..5 are written; object 0 and the
	// ego are placeholders: never observed, positions NaN.
	for (int r = 0; r <= kLastRobot; r++)
	{
		if (r == d.ego || !gt.count(r))
			g.objects.push_back(placeholderObject(r, steps.size()));
		else
			g.objects.push_back(robotObject(r, gt.at(r), steps, origin));
	}
	return g;
}
}  // namespace

TImportResult importRobot(const TDataset& d, const TImportOptions& opts)
{
	if (!(opts.group_window >= 0)) throw std::invalid_argument("group_window must be >= 0");
	std::map<int, CTrajectoryInterpolator> gt;
	for (const auto& [r, rows] : d.groundTruth) gt.emplace(r, CTrajectoryInterpolator(rows));
	if (!gt.count(d.ego))
		throw std::runtime_error("no ground truth for ego robot " + std::to_string(d.ego));
	const std::string measFile = robotFile(d.dir, d.ego, "Measurement");

	TImportResult res;
	auto& sum = res.summary;
	sum.dataset = d.dir;
	sum.ego = d.ego;
	sum.rows = d.measurements.size();

	double lo = 0, hi = 0;
	timeWindow(d, gt, opts.clip_to_ground_truth, lo, hi);
	res.steps = groupSteps(d, gt, opts, lo, hi, measFile, sum);
	std::vector<TStep>& steps = res.steps;
	if (steps.empty())
		throw std::runtime_error(measFile +
		                         ": no valid measurement inside the ground truth's time span");
	addOdometry(d, opts, steps);

	sum.steps = steps.size();
	sum.t_first = steps.front().t;
	sum.t_last = steps.back().t;
	for (const auto& [r, traj] : gt)
		if (r == d.ego || opts.clip_to_ground_truth)
			sum.max_gt_gap = std::max(sum.max_gt_gap, traj.maxGap(sum.t_first, sum.t_last));
	const Eigen::Vector3d origin = gt.at(d.ego).at(sum.t_first);
	sum.origin = origin;

	res.gt = groundTruthInFrame(d, gt, steps, origin);
	res.gt.checkConsistent();
	return res;
}
}  // namespace dynslam::mrclam
