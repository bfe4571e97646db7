#include "dynslam/eval/writers.h"

#include <dynslam/core/models/se2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <map>
#include <stdexcept>

namespace dynslam::eval
{
namespace
{
std::string num(double v)
{
	if (!std::isfinite(v)) return "";
	char buf[40];
	std::snprintf(buf, sizeof(buf), "%.9g", v);
	return buf;
}

/** Time stamps need more digits than num(): absolute times (1.6e9 s) would collapse. */
std::string numTime(double v)
{
	if (!std::isfinite(v)) return "";
	char buf[40];
	std::snprintf(buf, sizeof(buf), "%.15g", v);
	return buf;
}

double sig3(double var) { return 3.0 * std::sqrt(std::max(0.0, var)); }

double timeOf(const TEgoEstimate& e, const io::TGroundTruth* gt)
{
	if (std::isfinite(e.t)) return e.t;
	if (gt && e.step >= 0 && static_cast<size_t>(e.step) < gt->t.size()) return gt->t[e.step];
	return kNaN;
}

const io::TObjectGroundTruth* findObject(const io::TGroundTruth* gt, int32_t object)
{
	if (!gt) return nullptr;
	for (const auto& o : gt->objects)
		if (o.object == object) return &o;
	return nullptr;
}

std::vector<const TEgoEstimate*> sortedEgo(const std::vector<TEgoEstimate>& ego)
{
	std::vector<const TEgoEstimate*> v;
	for (const auto& e : ego) v.push_back(&e);
	std::sort(v.begin(), v.end(), [](auto a, auto b) { return a->step < b->step; });
	return v;
}
}  // namespace

void writeFile(const std::string& path, const std::function<void(std::ostream&)>& write)
{
	std::ofstream f(path);
	if (!f) throw std::runtime_error("cannot open '" + path + "' for writing");
	write(f);
	f.flush();
	if (!f) throw std::runtime_error("error while writing '" + path + "'");
}

void writeTum(std::ostream& os, const std::vector<TEgoEstimate>& ego, const io::TGroundTruth* gt)
{
	for (const TEgoEstimate* e : sortedEgo(ego))
	{
		const double t = timeOf(*e, gt);
		if (!std::isfinite(t))
			throw std::invalid_argument("writeTum: no time stamp for step " +
			                            std::to_string(e->step) +
			                            " (set TEgoEstimate::t or pass the ground truth)");
		const double th = e->mean[2];
		os << numTime(t) << " " << num(e->mean[0]) << " " << num(e->mean[1]) << " 0 0 0 "
		   << num(std::sin(0.5 * th)) << " " << num(std::cos(0.5 * th)) << "\n";
	}
}

void writeEgoCsv(std::ostream& os, const TRunEstimates& est, const io::TGroundTruth* gt)
{
	os << "step,t,x,y,theta,sigma3_x,sigma3_y,sigma3_theta,gt_x,gt_y,gt_theta,err_x,err_y,"
	      "err_theta,nees,nis,nis_dof\n";
	for (const TEgoEstimate* e : sortedEgo(est.ego))
	{
		os << e->step << "," << numTime(timeOf(*e, gt));
		for (int i = 0; i < 3; ++i) os << "," << num(e->mean[i]);
		for (int i = 0; i < 3; ++i) os << "," << num(sig3(e->cov(i, i)));
		if (gt && e->step < static_cast<int>(gt->numSteps()))
		{
			const Eigen::Vector3d& g = gt->ego[e->step];
			Eigen::Vector3d d = e->mean - g;
			d[2] = models::wrapToPi(d[2]);
			for (int i = 0; i < 3; ++i) os << "," << num(g[i]);
			for (int i = 0; i < 3; ++i) os << "," << num(d[i]);
			const auto nees = mahalanobis2(d, e->cov);
			os << "," << (nees ? num(*nees) : "");
		}
		else
			os << ",,,,,,,";
		const auto k = static_cast<size_t>(e->step);
		if (k < est.nis.size() && est.nis_dof[k] > 0)
			os << "," << num(est.nis[k]) << "," << est.nis_dof[k];
		else
			os << ",,0";
		os << "\n";
	}
}

void writeLandmarksCsv(std::ostream& os, const TRunEstimates& est, const io::TGroundTruth* gt)
{
	os << "id,x,y,sigma3_x,sigma3_y,gt_x,gt_y,err_x,err_y,nees\n";
	std::vector<const TLandmarkEstimate*> v;
	for (const auto& l : est.landmarks) v.push_back(&l);
	std::sort(v.begin(), v.end(), [](auto a, auto b) { return a->id < b->id; });
	for (const auto* l : v)
	{
		os << l->id << "," << num(l->mean[0]) << "," << num(l->mean[1]) << ","
		   << num(sig3(l->cov(0, 0))) << "," << num(sig3(l->cov(1, 1)));
		const auto it =
		    gt ? gt->landmarks.find(l->id) : std::map<int32_t, Eigen::Vector2d>::const_iterator();
		if (gt && it != gt->landmarks.end())
		{
			const Eigen::Vector2d d = l->mean - it->second;
			const auto nees = mahalanobis2(d, l->cov);
			os << "," << num(it->second[0]) << "," << num(it->second[1]) << "," << num(d[0]) << ","
			   << num(d[1]) << "," << (nees ? num(*nees) : "");
		}
		else
			os << ",,,,,";
		os << "\n";
	}
}

void writeObjectFeaturesCsv(std::ostream& os, const TRunEstimates& est, const io::TGroundTruth* gt)
{
	os << "object,feature,x,y,sigma3_x,sigma3_y,gt_x,gt_y,err_x,err_y\n";
	for (const auto& f : est.object_features)
	{
		os << f.object << "," << f.feature << "," << num(f.mean[0]) << "," << num(f.mean[1]) << ","
		   << num(sig3(f.cov(0, 0))) << "," << num(sig3(f.cov(1, 1)));
		const auto* o = findObject(gt, f.object);
		if (o && o->first_step >= 0 && f.feature >= 0 && f.feature < o->num_features)
		{
			const Eigen::Vector2d g = o->features[o->first_step].col(f.feature);
			os << "," << num(g[0]) << "," << num(g[1]) << "," << num(f.mean[0] - g[0]) << ","
			   << num(f.mean[1] - g[1]);
		}
		else
			os << ",,,,";
		os << "\n";
	}
}

void writeObjectPosesCsv(std::ostream& os, const TRunEstimates& est, const io::TGroundTruth* gt)
{
	os << "object,step,t,dx,dy,dtheta,sigma3_dx,sigma3_dy,sigma3_dtheta,gt_dx,gt_dy,gt_dtheta,"
	      "err_dx,err_dy,err_dtheta,nees,dof\n";
	for (const auto& p : est.object_poses)
	{
		const auto n = p.mean.size();
		const double t =
		    gt && p.step >= 0 && static_cast<size_t>(p.step) < gt->t.size() ? gt->t[p.step] : kNaN;
		os << p.object << "," << p.step << "," << numTime(t);
		for (int i = 0; i < 3; ++i) os << "," << (i < n ? num(p.mean[i]) : "");
		for (int i = 0; i < 3; ++i) os << "," << (i < n ? num(sig3(p.cov(i, i))) : "");
		const auto* o = findObject(gt, p.object);
		if (o && p.step >= 0 && p.step < static_cast<int>(o->pose.size()) &&
		    o->pose[p.step].allFinite())
		{
			const Eigen::Vector3d& g = o->pose[p.step];
			Eigen::VectorXd d = p.mean - g.head(n);
			if (n == 3) d[2] = models::wrapToPi(d[2]);
			for (int i = 0; i < 3; ++i) os << "," << num(g[i]);
			for (int i = 0; i < 3; ++i) os << "," << (i < n ? num(d[i]) : "");
			const auto nees = mahalanobis2(d, p.cov);
			os << "," << (nees ? num(*nees) : "");
		}
		else
			os << ",,,,,,,";
		os << "," << n << "\n";
	}
}

void writeObjectMotionCsv(std::ostream& os, const TRunEstimates& est, const io::TGroundTruth* gt)
{
	os << "object,step,t,vx,vy,omega,sigma3_vx,sigma3_vy,sigma3_omega";
	for (const auto& m : est.object_mode_names) os << ",p_" << m;
	os << "\n";
	const size_t nm = est.object_mode_names.size();
	for (const auto& p : est.object_poses)
	{
		const auto n = p.velocity.size();
		if (n == 0) continue;
		const double t =
		    gt && p.step >= 0 && static_cast<size_t>(p.step) < gt->t.size() ? gt->t[p.step] : kNaN;
		os << p.object << "," << p.step << "," << numTime(t);
		for (int i = 0; i < 3; ++i) os << "," << (i < n ? num(p.velocity[i]) : "");
		for (int i = 0; i < 3; ++i) os << "," << (i < n ? num(sig3(p.velocity_cov(i, i))) : "");
		for (size_t j = 0; j < nm; ++j)
			os << ","
			   << (size_t(p.mode_probabilities.size()) == nm
			           ? num(p.mode_probabilities[Eigen::Index(j)])
			           : "");
		os << "\n";
	}
}

namespace
{
size_t maxObjects(const std::vector<TMetricsRow>& rows)
{
	size_t k = 0;
	for (const auto& r : rows) k = std::max(k, r.metrics.objects.size());
	return k;
}
}  // namespace

/** The 12 tracking cells of a row (empty without scores). */
static void writeMotCells(std::ostream& os, const std::optional<TMetricsRow::TMotScores>& s)
{
	if (!s)
	{
		os << ",,,,,,,,,,,,";
		return;
	}
	const auto& m = *s;
	os << "," << m.cls << "," << num(m.iou.mota) << "," << num(m.iou.motp) << "," << m.iou.ids
	   << "," << m.iou.frag << "," << m.iou.fp << "," << m.iou.fn << "," << m.iou.gt << ","
	   << num(m.samota) << "," << num(m.dist.mota) << "," << num(m.dist.motp) << "," << m.dist.ids;
}

void writeMetricsCsv(std::ostream& os, const std::vector<TMetricsRow>& rows)
{
	const size_t K = maxObjects(rows);
	os << "filter,ego_rmse_x,ego_rmse_y,ego_rmse_theta,static_rmse_x,static_rmse_y,ate,ate_aligned,"
	      "ms_per_step,"
	      "ego_steps,landmarks_scored,landmarks_missing,landmarks_unmatched";
	for (size_t k = 1; k <= K; ++k)
	{
		const std::string a = "agent" + std::to_string(k);
		os << "," << a << "_object," << a << "_feat_rmse_x," << a << "_feat_rmse_y," << a
		   << "_pose_rmse_x," << a << "_pose_rmse_y," << a << "_pose_rmse_theta";
	}
	const bool classes =
	    std::any_of(rows.begin(), rows.end(), [](const TMetricsRow& r) { return r.classes; });
	if (classes) os << ",class_precision,class_recall,class_f1,group_ari";
	const bool gaps =
	    std::any_of(rows.begin(), rows.end(), [](const TMetricsRow& r) { return r.gap; });
	os << ",ego_anees,ego_nees_inside,map_anees,map_dof,nis_anees,nis_inside,"
	      "odometry_bias_rate_final,odometry_bias_scale_final";
	if (gaps)
		os << ",ate_gap,ate_outside_gap,err_gap_end,steps_gap,ego_nees_gap,ego_nees_gap_lower,"
		      "ego_nees_gap_upper";
	const bool velocities =
	    std::any_of(rows.begin(), rows.end(), [](const TMetricsRow& r) { return r.velocity; });
	if (velocities) os << ",obj_speed_rmse,obj_omega_rmse,obj_velocity_anees,obj_velocity_n";
	const bool memory =
	    std::any_of(rows.begin(), rows.end(), [](const TMetricsRow& r) { return r.peak_rss_mb; });
	if (memory) os << ",peak_rss_mb";
	const bool mot = std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.mot; });
	if (mot) os << ",mot_class,mota,motp,ids,frag,fp,fn,gt,samota,mota_d2,motp_d2,ids_d2";
	os << "\n";
	for (const auto& r : rows)
	{
		const TRunMetrics& m = r.metrics;
		os << r.filter << "," << num(m.ego.x) << "," << num(m.ego.y) << "," << num(m.ego.theta)
		   << "," << num(m.static_map.x) << "," << num(m.static_map.y) << "," << num(m.ate) << ","
		   << num(m.ate_aligned) << "," << num(m.ms_per_step) << "," << m.ego.n_xy << ","
		   << m.static_map.n_xy << "," << m.landmarks_missing << "," << m.landmarks_unmatched;
		for (size_t k = 0; k < K; ++k)
		{
			if (k >= m.objects.size())
			{
				os << ",,,,,,";
				continue;
			}
			const auto& o = m.objects[k];
			os << "," << o.object << "," << num(o.features.x) << "," << num(o.features.y) << ","
			   << num(o.poses.x) << "," << num(o.poses.y) << "," << num(o.poses.theta);
		}
		if (classes && r.classes)
			os << "," << num(r.classes->precision) << "," << num(r.classes->recall) << ","
			   << num(r.classes->f1) << "," << num(r.classes->ari);
		else if (classes)
			os << ",,,,";
		if (r.consistency)
		{
			const auto& c = *r.consistency;
			const int mapDof = c.map.rows.empty() ? 0 : c.map.rows.front().total_dof;
			os << "," << num(c.ego.anees) << "," << num(c.ego.fraction_inside) << ","
			   << num(c.map.anees) << "," << mapDof << "," << num(c.nis.anees) << ","
			   << num(c.nis.fraction_inside);
		}
		else
			os << ",,,,,,";
		os << "," << num(m.odometry_bias_rate) << "," << num(m.odometry_bias_scale);
		if (gaps && r.gap)
			os << "," << num(r.gap->ate) << "," << num(r.gap->ate_outside) << ","
			   << num(r.gap->err_end) << "," << r.gap->steps << "," << num(r.gap->nees) << ","
			   << num(r.gap->nees_lower) << "," << num(r.gap->nees_upper);
		else if (gaps)
			os << ",,,,,,,";
		if (velocities && r.velocity)
			os << "," << num(r.velocity->speed_rmse) << "," << num(r.velocity->omega_rmse) << ","
			   << num(r.velocity->anees) << "," << r.velocity->n;
		else if (velocities)
			os << ",,,,";
		if (memory) os << "," << (r.peak_rss_mb ? num(*r.peak_rss_mb) : "");
		if (mot) writeMotCells(os, r.mot);
		os << "\n";
	}
}

void writeMetricsTable(std::ostream& os, const std::vector<TMetricsRow>& rows)
{
	auto f = [](double v, int prec)
	{
		if (!std::isfinite(v)) return std::string("-");
		char buf[40];
		// huge values (a diverged filter) in scientific notation, so the columns stay aligned
		if (std::fabs(v) >= 1e5)
			std::snprintf(buf, sizeof(buf), "%.2e", v);
		else
			std::snprintf(buf, sizeof(buf), "%.*f", prec, v);
		return std::string(buf);
	};
	size_t w = 6;
	for (const auto& r : rows) w = std::max(w, r.filter.size());
	os << std::left << std::setw(static_cast<int>(w)) << "filter" << std::right << std::setw(11)
	   << "ego x [m]" << std::setw(11) << "ego y [m]" << std::setw(12) << "ego th[rad]"
	   << std::setw(11) << "map x [m]" << std::setw(11) << "map y [m]" << std::setw(10) << "ATE [m]"
	   << std::setw(10) << "ATEal [m]" << std::setw(10) << "ms/step" << std::setw(10) << "ego ANEES"
	   << std::setw(10) << "NIS in%"
	   << "\n";
	for (const auto& r : rows)
	{
		const auto& m = r.metrics;
		os << std::left << std::setw(static_cast<int>(w)) << r.filter << std::right << std::setw(11)
		   << f(m.ego.x, 4) << std::setw(11) << f(m.ego.y, 4) << std::setw(12) << f(m.ego.theta, 5)
		   << std::setw(11) << f(m.static_map.x, 4) << std::setw(11) << f(m.static_map.y, 4)
		   << std::setw(10) << f(m.ate, 4) << std::setw(10) << f(m.ate_aligned, 4) << std::setw(10)
		   << f(m.ms_per_step, 3) << std::setw(10)
		   << (r.consistency ? f(r.consistency->ego.anees, 2) : "-") << std::setw(10)
		   << (r.consistency ? f(100.0 * r.consistency->nis.fraction_inside, 1) : "-") << "\n";
	}
}

void writeConsistencyCsv(std::ostream& os, const TConsistencyStats& stats)
{
	os << "key,runs,total_dof,mean,lower,upper,inside\n";
	for (const auto& r : stats.rows)
		os << r.key << "," << r.runs << "," << r.total_dof << "," << num(r.mean) << ","
		   << num(r.lower) << "," << num(r.upper) << "," << (r.inside ? 1 : 0) << "\n";
}

void writeConsistencySummary(std::ostream& os, const TConsistencySummary& s)
{
	os << "NEES/NIS over " << s.runs << " run(s), two-sided " << (s.ego.confidence * 100.0)
	   << "% chi-square bounds"
	   << (s.map_joint_cov ? "" : " (map NEES: block-diagonal landmark covariance)") << "\n";
	auto line = [&](const TConsistencyStats& st)
	{
		char buf[200];
		std::snprintf(
		    buf, sizeof(buf),
		    "  %-16s rows %5zu  ANEES %9.3f in [%.3f, %.3f]  inside %5.1f%%  skipped %zu\n",
		    st.name.c_str(), st.rows.size(), st.anees, st.anees_lower, st.anees_upper,
		    100.0 * st.fraction_inside, st.skipped_singular);
		os << buf;
	};
	line(s.ego);
	line(s.landmarks);
	line(s.map);
	for (const auto& [o, st] : s.object_poses) line(st);
	line(s.nis);
}

void writeConsistencySummaryCsv(
    std::ostream& os, const std::vector<std::pair<std::string, TConsistencySummary>>& summaries)
{
	os << "label,block,runs,rows,anees,anees_lower,anees_upper,inside,fraction_inside,"
	      "skipped_singular\n";
	for (const auto& [label, s] : summaries)
	{
		auto row = [&, &label = label, &s = s](const TConsistencyStats& st)
		{
			os << label << "," << st.name << "," << s.runs << "," << st.rows.size() << ","
			   << num(st.anees) << "," << num(st.anees_lower) << "," << num(st.anees_upper) << ","
			   << st.inside << "," << num(st.fraction_inside) << "," << st.skipped_singular << "\n";
		};
		row(s.ego);
		row(s.landmarks);
		row(s.map);
		for (const auto& [o, st] : s.object_poses) row(st);
		row(s.nis);
	}
}
}  // namespace dynslam::eval
