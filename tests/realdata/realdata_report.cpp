/** dynslam-realdata-report: development tool of scripts/mrclam_results.sh (not a test). Runs
 * static_all, static_landmarks_only, dynamic and dynamic_nogate (realdata_run.h) on one imported
 * MRCLAM rawlog and writes, into --out:
 *   summary.csv          one row per filter (the columns of doc/results/real-data.md, section 5)
 *   tracked_robots.csv   per filter and robot: sightings scored, position RMSE, NEES
 *   tracked_positions.csv every online estimate p_t = f_0 + xi_t with its truth
 *   tracked.png          the other robots' true paths and the dynamic filter's estimates
 *                        (steps with t in [--t0, --t1] s from the start)
 *   map.png              ego paths and final landmarks of the filters over the ground truth */
#include <dynslam/apps/data_files.h>
#include <dynslam/eval/figures.h>
#include <dynslam/eval/plot_canvas.h>
#include <dynslam/eval/writers.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "realdata_run.h"

using namespace dynslam;

namespace
{
/** The other robots' true paths and the dynamic filter's online estimates, steps with
 * t - t_0 in [t0, t1]. */
void drawTracked(const io::TGroundTruth& gt, const realdata::TRealDataResult& r, double t0,
                 double t1, const std::string& path)
{
	auto inWindow = [&](size_t k)
	{ return gt.t[k] - gt.t.front() >= t0 && gt.t[k] - gt.t.front() <= t1; };
	mrpt::img::CImage img(1100, 1000, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, 1099, 999, mrpt::img::TColor(255, 255, 255));
	eval::TBox box = eval::TBox::empty();
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		if (!inWindow(k)) continue;
		box.expand(gt.ego[k].x(), gt.ego[k].y());
		for (const auto& o : gt.objects) box.expand(o.features[k](0, 0), o.features[k](1, 0));
	}
	eval::CPlotCanvas c(img, 80, 60, 980, 880, box.withMargin(0.03), true);
	std::vector<eval::TLegendEntry> legend;
	std::vector<Eigen::Vector2d> ego;
	for (size_t k = 0; k < gt.numSteps(); ++k)
		if (inWindow(k)) ego.emplace_back(gt.ego[k].x(), gt.ego[k].y());
	c.polyline(ego, mrpt::img::TColor(0, 0, 0), 2);
	legend.push_back({"ego ground truth", mrpt::img::TColor(0, 0, 0), 0});
	size_t ci = 1;
	for (const auto& o : gt.objects)
	{
		if (o.first_step < 0) continue;
		const auto col = eval::seriesColor(ci++);
		std::vector<Eigen::Vector2d> path;
		for (size_t k = 0; k < gt.numSteps(); ++k)
			if (inWindow(k)) path.emplace_back(o.features[k](0, 0), o.features[k](1, 0));
		c.polyline(path, eval::lighter(col, 0.4), 2);
		for (const auto& p : r.tracked)
			if (p.object == o.object && inWindow(size_t(p.step)))
			{
				c.mark(p.est.x(), p.est.y(), col, 'x', 4);
				c.line(p.est.x(), p.est.y(), p.truth.x(), p.truth.y(), eval::lighter(col, 0.2), 1);
			}
		legend.push_back(
		    {"robot " + std::to_string(o.object) + ": truth (line), estimates (x)", col, 'x'});
	}
	std::ostringstream title;
	title << "Dynamic EKF, other robots, t = " << t0 << ".." << t1
	      << " s: x = f_0 + xi_t after step t, line to the truth";
	c.axes("x [m]", "y [m]", title.str());
	c.legend(legend);
	eval::savePng(img, path);
}

/** Ego paths and final maps of the filters over the ground truth, metric (equal aspect). */
void drawFilterMaps(const io::TGroundTruth& gt,
                    const std::vector<realdata::TRealDataResult>& results, const std::string& label,
                    const std::string& path)
{
	std::vector<eval::TFigureSeries> series;
	const size_t colors[] = {0, 3, 1, 2};
	for (size_t i = 0; i < results.size(); ++i)
		series.push_back({results[i].filter, eval::seriesColor(colors[i]), &results[i].run.est});
	eval::TMapFigureOptions mo;
	mo.width = 1300;
	mo.height = 1000;
	mo.equal_aspect = true;
	mo.show_objects = false;
	eval::TBox box = eval::TBox::empty();
	for (const auto& x : gt.ego) box.expand(x.x(), x.y());
	for (const auto& [id, p] : gt.landmarks) box.expand(p.x(), p.y());
	mo.view = box.withMargin(0.05);
	mo.title = label + ": ego paths and final landmarks (3-sigma) over the ground truth";
	eval::savePng(eval::drawMapFigure(&gt, series, mo), path);
}
}  // namespace

int main(int argc, char** argv)
{
	try
	{
		TCLAP::CmdLine cmd("dynslam-realdata-report (see scripts/mrclam_results.sh)", ' ', "0.1");
		TCLAP::ValueArg<std::string> aRaw("r", "rawlog", "imported rawlog", true, "", "file", cmd);
		TCLAP::ValueArg<std::string> aCfg("c", "config", "INI (config/mrclam_compare.ini)", true,
		                                  "", "ini", cmd);
		TCLAP::ValueArg<std::string> aOut("o", "out", "output folder", true, "", "dir", cmd);
		TCLAP::ValueArg<std::string> aLabel("l", "label", "row label (e.g. robot3)", false, "", "s",
		                                    cmd);
		TCLAP::ValueArg<double> aT0("", "t0", "tracked.png from t0 [s]", false, 0, "s", cmd);
		TCLAP::ValueArg<double> aT1("", "t1", "tracked.png until t1 [s]", false, 120, "s", cmd);
		cmd.parse(argc, argv);

		const auto raw = apps::loadRawlog(aRaw.getValue());
		const std::string gtSpec = apps::groundTruthBesideRawlog(aRaw.getValue());
		if (gtSpec.empty()) throw std::runtime_error("no ground truth beside " + aRaw.getValue());
		const io::TGroundTruth gt = apps::loadGroundTruthFor(gtSpec, raw.size(), aRaw.getValue());
		mrpt::config::CConfigFileMemory ini;
		apps::loadIniFile(aCfg.getValue(), ini);
		const std::string out = aOut.getValue();
		std::filesystem::create_directories(out);

		std::ofstream sum(out + "/summary.csv"), trk(out + "/tracked_robots.csv"),
		    pos(out + "/tracked_positions.csv");
		sum << "label,filter,steps,ate,landmark_rmse,landmarks_scored,ego_anees,ego_anees_lo,"
		       "ego_anees_hi,ego_frac_in,nis_anis,nis_anis_lo,nis_anis_hi,nis_frac_in,gated_out,"
		       "static_updates,tracked_n,tracked_rmse,tracked_mean_nees,tracked_frac_in95,ms_per_"
		       "step\n";
		trk << "label,filter,object,n,rmse,mean_nees,frac_in95\n";
		pos << "label,filter,object,step,t,est_x,est_y,truth_x,truth_y,nees\n";
		std::vector<realdata::TRealDataResult> results;
		for (const std::string f :
		     {"static_all", "static_landmarks_only", "dynamic", "dynamic_nogate"})
		{
			results.push_back(realdata::runRealData(raw, gt, ini, f));
			const auto& r = results.back();
			const auto& e = r.eval.summary.ego;
			const auto& n = r.eval.summary.nis;
			sum << aLabel.getValue() << "," << f << "," << r.run.steps << "," << r.ate << ","
			    << r.landmark_rmse << "," << r.landmarks_scored << "," << e.anees << ","
			    << e.anees_lower << "," << e.anees_upper << "," << e.fraction_inside << ","
			    << n.anees << "," << n.anees_lower << "," << n.anees_upper << ","
			    << n.fraction_inside << "," << r.gated_out << "," << r.static_updates << ","
			    << r.tracked_all.n << "," << r.tracked_all.rmse << "," << r.tracked_all.mean_nees
			    << "," << r.tracked_all.frac_nees_in95 << "," << r.run.est.ms_per_step << "\n";
			for (const auto& [obj, s] : r.tracked_by_robot)
				trk << aLabel.getValue() << "," << f << "," << obj << "," << s.n << "," << s.rmse
				    << "," << s.mean_nees << "," << s.frac_nees_in95 << "\n";
			for (const auto& p : r.tracked)
				pos << aLabel.getValue() << "," << f << "," << p.object << "," << p.step << ","
				    << gt.t[size_t(p.step)] << "," << p.est.x() << "," << p.est.y() << ","
				    << p.truth.x() << "," << p.truth.y() << "," << p.nees << "\n";
			if (f == "dynamic")
				drawTracked(gt, r, aT0.getValue(), aT1.getValue(), out + "/tracked.png");
			std::cout << f << ": ATE " << r.ate << " m, landmarks " << r.landmark_rmse
			          << " m, tracked " << r.tracked_all.rmse << " m (" << r.tracked_all.n
			          << "), gated " << r.gated_out << ", " << r.run.est.ms_per_step
			          << " ms/step\n";
		}
		drawFilterMaps(gt, results, aLabel.getValue(), out + "/map.png");
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-realdata-report: error: " << e.what() << "\n";
		return 1;
	}
}
