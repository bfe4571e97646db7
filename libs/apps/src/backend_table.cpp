#include <dynslam/apps/backend_table.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/eval/consistency.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/framework/CWindowBackend.h>
#include <dynslam/framework/backend_factory.h>
#include <dynslam/sim/scenario.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>

namespace dynslam::apps
{
using namespace dynslam::framework;
namespace
{
/** Pooled sums of squared errors for the RMSE over runs. */
struct TAcc
{
	double s[13] = {0};
	size_t n[13] = {0};
	void add(int i, double rmse, size_t cnt)
	{
		if (cnt == 0 || !std::isfinite(rmse)) return;
		s[i] += rmse * rmse * double(cnt);
		n[i] += cnt;
	}
	double get(int i) const { return n[i] ? std::sqrt(s[i] / double(n[i])) : std::nan(""); }
};

eval::TRunEstimates collect(ISlamBackend& be, const std::vector<eval::TEgoEstimate>& ego, double ms)
{
	eval::TRunEstimates e;
	e.ego = ego;
	for (const auto& l : allStaticLandmarks(be)) e.landmarks.push_back({l.id, l.mean, l.cov});
	for (const auto& f : be.getObjectFeatures())
		if (f.at_time0) e.object_features.push_back({f.object, f.feature, f.mean, f.cov});
	for (const auto& [obj, tr] : be.getObjectTracks())
		for (const auto& p : tr.poses)
			e.object_poses.push_back(
			    {obj, p.step, p.mean, p.cov, p.velocity, p.velocity_cov, p.mode_probabilities});
	e.ms_per_step = ms;
	return e;
}

std::unique_ptr<ISlamBackend> create(const std::string& kind, const sim::TScenarioOptions& so,
                                     const TBackendTableOptions& o)
{
	CDynamicKFSLAM2D::TOptions m;
	m.measurement_model = so.noise_model;
	m.Sigma_v =
	    so.noise_model == models::MeasurementModel::Cartesian
	        ? so.Sigma_v
	        : Eigen::Matrix2d(Eigen::Vector2d(so.std_range * so.std_range, so.std_yaw * so.std_yaw)
	                              .asDiagonal());
	m.motion_noise_from_action = true;
	m.Sigma_0 = so.Sigma_0;
	m.Sigma_xi = Eigen::Matrix2d::Identity() * o.sigma_xi;
	if (kind == "dynamic_ekf")
	{
		auto ekf = std::make_unique<CDynamicKFSLAM2D>();
		ekf->options = m;
		ekf->reset();
		return ekf;
	}
	TBackendOptions b = defaultBackendOptions(kind);
	b.model = m;
	if (b.window_size > 0 && kind != "alg1") b.window_size = o.window_size;
	return makeBackend(b);
}
}  // namespace

namespace
{
/** Runs one back-end over a simulated run: its ego estimates per step and the mean ms/step. */
std::vector<eval::TEgoEstimate> runOnce(ISlamBackend& be, const sim::TSimulatedRun& run,
                                        double& msPerStep)
{
	std::vector<eval::TEgoEstimate> ego;
	double ms = 0;
	for (size_t k = 0; k < run.actions.size(); ++k)
	{
		const auto t0 = std::chrono::steady_clock::now();
		be.processActionObservation(run.actions[k], run.frames[k]);
		const auto p = be.getEgoPose();
		ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
		          .count();
		eval::TEgoEstimate e;
		e.step = int(k);
		e.mean = Eigen::Vector3d(p.mean.x(), p.mean.y(), p.mean.phi());
		e.cov = p.cov.asEigen();
		ego.push_back(e);
	}
	msPerStep = ms / double(run.actions.size());
	return ego;
}

/** Final-trajectory errors x, y (columns 10, 11) and the RPE over 10 steps (column 12). */
void scoreFinalTrajectory(const std::map<int, Eigen::Vector3d>& fin, const io::TGroundTruth& gt,
                          TAcc& a)
{
	double sx = 0, sy = 0;
	for (const auto& [k, v] : fin)
	{
		sx += std::pow(v[0] - gt.ego[size_t(k)][0], 2);
		sy += std::pow(v[1] - gt.ego[size_t(k)][1], 2);
	}
	a.add(10, std::sqrt(sx / double(fin.size())), fin.size());
	a.add(11, std::sqrt(sy / double(fin.size())), fin.size());
	// Relative pose error over 10 steps of the final trajectory (drift removed).
	double sr = 0;
	size_t nr = 0;
	for (const auto& [k, v] : fin)
	{
		const auto it = fin.find(k + 10);
		if (it == fin.end()) continue;
		const Eigen::Vector3d de = models::poseDifference(it->second, v);
		const Eigen::Vector3d dg =
		    models::poseDifference(gt.ego[size_t(k + 10)], gt.ego[size_t(k)]);
		sr += (de.head<2>() - dg.head<2>()).squaredNorm();
		++nr;
	}
	if (nr) a.add(12, std::sqrt(sr / double(nr)), nr);
}

/** Table I errors of one run (columns 0-9). */
void addRunMetrics(const eval::TRunMetrics& m, TAcc& a)
{
	a.add(0, m.ego.x, m.ego.n_xy);
	a.add(1, m.ego.y, m.ego.n_xy);
	a.add(2, m.ego.theta, m.ego.n_theta);
	a.add(3, m.static_map.x, m.static_map.n_xy);
	a.add(4, m.static_map.y, m.static_map.n_xy);
	for (const auto& ob : m.objects)
	{
		a.add(5, ob.features.x, ob.features.n_xy);
		a.add(6, ob.features.y, ob.features.n_xy);
		a.add(7, ob.poses.x, ob.poses.n_xy);
		a.add(8, ob.poses.y, ob.poses.n_xy);
		a.add(9, ob.poses.theta, ob.poses.n_theta);
	}
}

/** The row of one kind from its accumulated errors and consistency samples. */
TBackendTableRow finishRow(TBackendTableRow row, const TAcc& a,
                           const std::vector<eval::TRunConsistency>& cons)
{
	row.ego_x = a.get(0);
	row.ego_y = a.get(1);
	row.ego_theta = a.get(2);
	row.map_x = a.get(3);
	row.map_y = a.get(4);
	row.feat_x = a.get(5);
	row.feat_y = a.get(6);
	row.pose_x = a.get(7);
	row.pose_y = a.get(8);
	row.pose_theta = a.get(9);
	row.final_x = a.get(10);
	row.final_y = a.get(11);
	row.rpe10 = a.get(12);
	double se = 0, de = 0, sp = 0, dp = 0;
	for (const auto& c : cons)
	{
		for (const auto& s : c.ego.samples) se += s.value, de += s.dof;
		for (const auto& [obj, ps] : c.object_poses)
			for (const auto& s : ps.samples) sp += s.value, dp += s.dof;
	}
	row.anees_ego = de > 0 ? se / de : std::nan("");
	row.anees_pose = dp > 0 ? sp / dp : std::nan("");
	if (row.runs > 0) row.ms_per_step /= row.runs;
	return row;
}
}  // namespace

std::vector<TBackendTableRow> runBackendTable(const TBackendTableOptions& o)
{
	sim::TScenarioOptions so = sim::loadScenario(o.scenario_ini);
	so.setNoiseLevel(o.noise_level);
	if (o.steps > 0) so.steps = o.steps;
	const io::TGroundTruth gt = sim::buildGroundTruth(so);
	std::vector<std::string> kinds = o.kinds;
	if (kinds.empty())
	{
		kinds.push_back("dynamic_ekf");
		for (const auto& k : backendKinds()) kinds.push_back(k);
	}
	std::map<std::string, TAcc> acc;
	std::map<std::string, std::vector<eval::TRunConsistency>> cons;
	std::map<std::string, TBackendTableRow> rows;
	for (int r = 0; r < o.runs; ++r)
	{
		const auto run = sim::simulateMeasurements(gt, so, uint64_t(r + 1));
		for (const auto& kind : kinds)
		{
			TBackendTableRow& row = rows[kind];
			row.kind = kind;
			try
			{
				auto be = create(kind, so, o);
				double ms = 0;
				const std::vector<eval::TEgoEstimate> ego = runOnce(*be, run, ms);
				const auto est = collect(*be, ego, ms);
				std::map<int, Eigen::Vector3d> fin;
				if (const auto* w = dynamic_cast<const CWindowBackend*>(be.get()))
					fin = w->finalTrajectory();
				else
					for (const auto& e : ego) fin[e.step] = e.mean;
				scoreFinalTrajectory(fin, gt, acc[kind]);
				addRunMetrics(eval::computeRunMetrics(gt, est), acc[kind]);
				cons[kind].push_back(eval::computeRunConsistency(gt, est));
				row.ms_per_step += est.ms_per_step;
				++row.runs;
			}
			catch (const std::exception& e)
			{
				if (row.failures++ == 0) row.failure = e.what();
			}
		}
	}
	std::vector<TBackendTableRow> out;
	for (const auto& kind : kinds) out.push_back(finishRow(rows[kind], acc[kind], cons[kind]));
	return out;
}

void writeBackendTableMarkdown(std::ostream& os, const std::vector<TBackendTableRow>& rows)
{
	os << "| back-end | runs | ego x | ego y | ego theta | final ego x | final ego y | map x | map "
	      "y | "
	      "feature x | feature y | pose x | pose y | pose theta | RPE10 | ANEES ego | ANEES pose | "
	      "ms/step |\n";
	os << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
	os << std::setprecision(3);
	for (const auto& r : rows)
	{
		os << "| " << r.kind << " | " << r.runs;
		if (r.failures) os << " (" << r.failures << " failed)";
		for (double v : {r.ego_x, r.ego_y, r.ego_theta, r.final_x, r.final_y, r.map_x, r.map_y,
		                 r.feat_x, r.feat_y, r.pose_x, r.pose_y, r.pose_theta, r.rpe10, r.anees_ego,
		                 r.anees_pose, r.ms_per_step})
			os << " | " << v;
		os << " |\n";
	}
	for (const auto& r : rows)
		if (r.failures) os << "\n" << r.kind << ": first failure: " << r.failure << "\n";
}
}  // namespace dynslam::apps
