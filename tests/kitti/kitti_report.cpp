/** dynslam-kitti-report: development tool of scripts/kitti_results.sh (not a test). Runs
 * static_all, static_landmarks_only, dynamic and dynamic_nogate (kitti_run.h; --filters) on one
 * imported KITTI rawlog (ground truth and <base>_scenario.ini beside it) and writes, into --out:
 *   summary.csv   one row per filter: the columns of doc/kitti.md's tables, the annotation
 *                 jitter floor of the import, the sequence's counts
 *   objects.csv   per tracked object (dynamic filters): position RMSE, motion errors
 *   map.png       ego paths of the filters over the truth, parked cars (the static landmarks)
 *                 and the object tracks (truth and the dynamic filter's estimates), metric */
#include <dynslam/apps/data_files.h>
#include <dynslam/eval/figures.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "kitti_run.h"

using namespace dynslam;

namespace
{
constexpr double kDeg = 180.0 / M_PI;

void drawMap(const io::TGroundTruth& gt, const std::vector<kitti_eval::TKittiRunResult>& results,
             const std::string& label, const std::string& path)
{
	std::vector<eval::TFigureSeries> series;
	const size_t colors[] = {0, 3, 1, 2};
	for (size_t i = 0; i < results.size(); ++i)
		series.push_back(
		    {results[i].filter, eval::seriesColor(colors[i % 4]), &results[i].run.est});
	eval::TMapFigureOptions mo;
	mo.width = 1400;
	mo.height = 1100;
	mo.equal_aspect = true;
	mo.show_ellipses = false;
	eval::TBox box = eval::TBox::empty();
	for (const auto& x : gt.ego) box.expand(x.x(), x.y());
	for (const auto& [id, p] : gt.landmarks) box.expand(p.x(), p.y());
	mo.view = box.withMargin(0.05);
	mo.title =
	    label + ": ego paths, parked cars (static landmarks) and object tracks over the truth";
	eval::savePng(eval::drawMapFigure(&gt, series, mo), path);
}

/** One row of summary.csv (and objects.csv for the dynamic filters). */
void writeRow(std::ostream& sum, std::ostream& obj, const std::string& label,
              const kitti_eval::TKittiRunResult& r, const mrpt::config::CConfigFileBase& sc)
{
	const char* R = "KITTI_ImportResult";
	const std::string& f = r.filter;
	const bool dyn = f.rfind("dynamic", 0) == 0;
	const auto& m = r.objects.motion;
	auto val = [&](double v) { return dyn ? std::to_string(v) : std::string(); };
	sum << label << ',' << f << ',' << r.run.steps << ',' << sc.read_double(R, "path_length", 0)
	    << ',' << sc.read_int(R, "moving_tracks", 0) << ',' << sc.read_int(R, "static_tracks", 0)
	    << ',' << r.ate << ',' << r.rpe.trans_rmse << ',' << r.rpe.rot_rmse * kDeg << ','
	    << r.map_rmse << ',' << r.landmarks_scored << ',' << val(r.objects.position_rmse) << ','
	    << (dyn ? std::to_string(r.objects.position_n) : "") << ',' << val(m.trans_rmse) << ','
	    << val(m.rot_rmse * kDeg) << ',' << val(m.trans_mean) << ',' << val(m.rot_mean * kDeg)
	    << ',' << (dyn ? std::to_string(m.n) : "") << ','
	    << sc.read_double(R, "floor_trans_rmse", NAN) << ','
	    << sc.read_double(R, "floor_rot_rmse", NAN) * kDeg << ',' << sc.read_int(R, "floor_n", 0)
	    << ',' << sc.read_double(R, "static_corner_rms", NAN) << ',' << r.gated_out << ','
	    << r.static_updates << ',' << r.run.est.ms_per_step << ',' << r.eval.summary.ego.anees
	    << ',';
	if (r.velocity)
		sum << r.velocity->speed_rmse << ',' << r.velocity->omega_rmse << ',' << r.velocity->anees
		    << ',' << r.velocity->n << ',';
	else
		sum << ",,,,";
	sum << val(r.objects_seen.position_rmse) << ','
	    << (dyn ? std::to_string(r.objects_seen.position_n) : "") << ',';
	if (r.velocity_seen)
		sum << r.velocity_seen->speed_rmse << ',' << r.velocity_seen->n << "\n";
	else
		sum << ",\n";
	if (dyn)
		for (const auto& [o, e] : r.objects.motion_per_object)
			obj << label << ',' << f << ',' << o << ',' << r.objects.position_rmse_per_object.at(o)
			    << ',' << e.n << ',' << e.trans_rmse << ',' << e.rot_rmse * kDeg << "\n";
}
}  // namespace

int main(int argc, char** argv)
{
	try
	{
		TCLAP::CmdLine cmd("dynslam-kitti-report (see scripts/kitti_results.sh)", ' ', "0.1");
		TCLAP::ValueArg<std::string> aRaw("r", "rawlog", "imported rawlog", true, "", "file", cmd);
		TCLAP::ValueArg<std::string> aCfg("c", "config", "INI (config/compare_kitti.ini)", true, "",
		                                  "ini", cmd);
		TCLAP::ValueArg<std::string> aOut("o", "out", "output folder", true, "", "dir", cmd);
		TCLAP::ValueArg<std::string> aLabel("l", "label", "row label (e.g. 0000)", false, "", "s",
		                                    cmd);
		TCLAP::ValueArg<std::string> aFilters(
		    "", "filters", "comma-separated filters", false,
		    "static_all,static_landmarks_only,dynamic,dynamic_nogate", "list", cmd);
		cmd.parse(argc, argv);

		const std::string rawPath = aRaw.getValue(), label = aLabel.getValue();
		const auto raw = apps::loadRawlog(rawPath);
		const std::string gtSpec = apps::groundTruthBesideRawlog(rawPath);
		if (gtSpec.empty()) throw std::runtime_error("no ground truth beside " + rawPath);
		const io::TGroundTruth gt = apps::loadGroundTruthFor(gtSpec, raw.size(), rawPath);
		const std::string scen = apps::scenarioBesideRawlog(rawPath);
		if (!std::filesystem::exists(scen)) throw std::runtime_error(scen + ": not found");
		mrpt::config::CConfigFile sc(scen);
		const char* R = "KITTI_ImportResult";
		mrpt::config::CConfigFileMemory ini;
		apps::loadIniFile(aCfg.getValue(), ini);
		const std::string out = aOut.getValue();
		std::filesystem::create_directories(out);

		std::ofstream sum(out + "/summary.csv"), obj(out + "/objects.csv");
		sum << "label,filter,steps,path_length,moving_tracks,static_tracks,ate,rpe10_t,rpe10_r_deg,"
		       "map_rmse,landmarks_scored,obj_pos_rmse,obj_pos_n,motion_t_rmse,motion_r_rmse_deg,"
		       "motion_t_mean,motion_r_mean_deg,motion_n,floor_t_rmse,floor_r_rmse_deg,floor_n,"
		       "static_corner_rms,gated_out,static_updates,ms_per_step,ego_anees,obj_speed_rmse,"
		       "obj_omega_rmse,obj_velocity_anees,obj_velocity_n,obj_pos_rmse_seen,obj_pos_n_seen,"
		       "obj_speed_rmse_seen,obj_velocity_n_seen\n";
		obj << "label,filter,object,pos_rmse,motion_n,motion_t_rmse,motion_r_rmse_deg\n";
		std::vector<kitti_eval::TKittiRunResult> results;
		const auto odo = kitti_eval::deadReckoning(raw, gt);
		sum << label << ",odometry," << raw.size() << ',' << sc.read_double(R, "path_length", 0)
		    << ',' << sc.read_int(R, "moving_tracks", 0) << ','
		    << sc.read_int(R, "static_tracks", 0) << ',' << odo.ate << ',' << odo.rpe.trans_rmse
		    << ',' << odo.rpe.rot_rmse * kDeg << ",,,,,,,,,,"
		    << sc.read_double(R, "floor_trans_rmse", NAN) << ','
		    << sc.read_double(R, "floor_rot_rmse", NAN) * kDeg << ','
		    << sc.read_int(R, "floor_n", 0) << ',' << sc.read_double(R, "static_corner_rms", NAN)
		    << ",,,,,,,,,,,,\n";
		for (const std::string& f : apps::splitList(aFilters.getValue()))
		{
			try
			{
				results.push_back(kitti_eval::runKitti(raw, gt, ini, f));
			}
			catch (const std::exception& e)
			{
				// a filter that diverges (NaN state) is a result, not a reason to stop
				std::cout << label << " " << f << ": FAILED: " << e.what() << "\n";
				sum << label << ',' << f << ",failed,,,,nan,nan,nan,nan,,,,,,,,,,,,,,,,,,,,,,,,\n";
				continue;
			}
			const auto& r = results.back();
			writeRow(sum, obj, label, r, sc);
			const auto& m = r.objects.motion;
			std::cout << label << " " << f << ": ATE " << r.ate << " m, RPE10 " << r.rpe.trans_rmse
			          << " m, map " << r.map_rmse << " m, objects " << r.objects.position_rmse
			          << " m, motion " << m.trans_rmse << " m / " << m.rot_rmse * kDeg << " deg, "
			          << r.run.est.ms_per_step << " ms/step\n";
		}
		drawMap(gt, results, label, out + "/map.png");
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-kitti-report: error: " << e.what() << "\n";
		return 1;
	}
}
