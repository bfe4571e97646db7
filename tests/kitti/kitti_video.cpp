/** dynslam-kitti-video: development tool (not a test). Runs the dynamic EKF
 * (config/compare_kitti.ini) on an imported KITTI rawlog and writes an MJPG video (OpenCV
 * VideoWriter), one frame per step: the ego view (a window that follows the true ego, world axes),
 * the true and estimated ego paths, the ego's 3-sigma ellipse, the static landmarks (truth and
 * estimates with ellipses), the moving objects' true corners and the estimated object positions
 * (centroid of f_0 moved by the latest xi) with their 3-sigma ellipses. doc/kitti.md, section 5. */
#include <dynslam/apps/data_files.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/eval/figures.h>
#include <dynslam/eval/plot_canvas.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "kitti_run.h"

using namespace dynslam;

namespace
{
const mrpt::img::TColor kBlack(0, 0, 0), kGrey(150, 150, 150), kBlue(30, 80, 220),
    kGreen(20, 150, 40), kRed(220, 40, 40);

/** Estimated object positions: centroid of f_0 + (dx, dy) of the latest pose, with the pose's
 * 2x2 covariance (the f_0 uncertainty is not added: a lower bound of the position's). */
void drawObjects(eval::CPlotCanvas& c, const CDynamicKFSLAM2D& f)
{
	std::map<int32_t, std::pair<Eigen::Vector2d, int>> c0;
	for (const auto& fe : f.getObjectFeatures())
		if (fe.at_time0)
		{
			auto it =
			    c0.emplace(fe.object, std::make_pair(Eigen::Vector2d::Zero().eval(), 0)).first;
			auto& e = it->second;
			e.first += fe.mean;
			e.second += 1;
		}
	for (const auto& [obj, tr] : f.getObjectTracks())
	{
		if (tr.poses.empty() || !c0.count(obj)) continue;
		const auto& p = tr.poses.back();
		const Eigen::Vector2d pos = c0[obj].first / double(c0[obj].second) + p.mean.head<2>();
		c.mark(pos.x(), pos.y(), kRed, 's', 5);
		c.ellipse(pos, p.cov.topLeftCorner<2, 2>(), 3, kRed, 1);
	}
}

mrpt::img::CImage drawFrame(const io::TGroundTruth& gt, const CDynamicKFSLAM2D& f, size_t k,
                            const std::vector<Eigen::Vector2d>& estPath)
{
	mrpt::img::CImage img(960, 720, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, 959, 719, mrpt::img::TColor(255, 255, 255));
	const Eigen::Vector3d& e = gt.ego[k];
	eval::TBox box{e.x() - 35, e.x() + 35, e.y() - 26, e.y() + 26};
	eval::CPlotCanvas c(img, 60, 40, 880, 640, box, true);
	std::vector<Eigen::Vector2d> truePath;
	for (size_t j = 0; j <= k; ++j) truePath.push_back(gt.ego[j].head<2>());
	c.polyline(truePath, kBlack, 2);
	c.polyline(estPath, kBlue, 2);
	for (const auto& [id, p] : gt.landmarks) c.mark(p.x(), p.y(), kGrey, 'x', 3);
	for (const auto& l : f.getStaticLandmarks())
	{
		c.mark(l.mean.x(), l.mean.y(), kBlue, '+', 3);
		c.ellipse(l.mean, l.cov, 3, kBlue, 1);
	}
	for (const auto& o : gt.objects)
		if (o.visible[k])
			for (int j = 0; j < o.num_features; ++j)
			{
				const Eigen::Vector2d a = o.features[k].col(j), b = o.features[k].col((j + 1) % 4);
				c.line(a.x(), a.y(), b.x(), b.y(), kGreen, 2);
			}
	drawObjects(c, f);
	const auto ego = f.getEgoPose();
	Eigen::Matrix2d P;
	P << ego.cov(0, 0), ego.cov(0, 1), ego.cov(1, 0), ego.cov(1, 1);
	const Eigen::Vector2d m(ego.mean.x(), ego.mean.y());
	c.ellipse(m, P, 3, kBlue, 2);
	c.line(m.x(), m.y(), m.x() + 3 * std::cos(ego.mean.phi()), m.y() + 3 * std::sin(ego.mean.phi()),
	       kBlue, 2);
	std::ostringstream t;
	t.precision(3);
	t << "step " << k << ", t = " << gt.t[k]
	  << " s: truth black/grey x/green boxes; dynamic EKF blue (3-sigma), objects red";
	c.axes("x [m]", "y [m]", t.str());
	return img;
}
}  // namespace

int main(int argc, char** argv)
{
	try
	{
		TCLAP::CmdLine cmd("dynslam-kitti-video (development tool, doc/kitti.md)", ' ', "0.1");
		TCLAP::ValueArg<std::string> aRaw("r", "rawlog", "imported rawlog", true, "", "file", cmd);
		TCLAP::ValueArg<std::string> aCfg("c", "config", "INI (config/compare_kitti.ini)", true, "",
		                                  "ini", cmd);
		TCLAP::ValueArg<std::string> aOut("o", "out", "output video (.avi, MJPG)", true, "", "file",
		                                  cmd);
		TCLAP::ValueArg<int> aSnap("", "snapshot",
		                           "also save the frame of this step as PNG (beside the video)",
		                           false, -1, "step", cmd);
		cmd.parse(argc, argv);
		const auto raw = apps::loadRawlog(aRaw.getValue());
		const io::TGroundTruth gt = apps::loadGroundTruthFor(
		    apps::groundTruthBesideRawlog(aRaw.getValue()), raw.size(), aRaw.getValue());
		mrpt::config::CConfigFileMemory ini;
		apps::loadIniFile(aCfg.getValue(), ini);
		auto backend = apps::makeBackend("ekf", ini);
		const auto* dyn = dynamic_cast<const CDynamicKFSLAM2D*>(backend.get());
		if (!dyn) throw std::runtime_error("the ekf back-end is not a CDynamicKFSLAM2D");
		cv::VideoWriter video(aOut.getValue(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10,
		                      cv::Size(960, 720));
		if (!video.isOpened()) throw std::runtime_error(aOut.getValue() + ": cannot open video");
		std::vector<Eigen::Vector2d> estPath;
		for (size_t k = 0; k < raw.size(); ++k)
		{
			backend->processActionObservation(raw.actions[k], raw.frames[k]);
			const auto e = dyn->getEgoPose().mean;
			estPath.emplace_back(e.x(), e.y());
			const auto img = drawFrame(gt, *dyn, k, estPath);
			cv::Mat m = img.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
			video.write(m);
			if (int(k) == aSnap.getValue()) eval::savePng(img, aOut.getValue() + ".png");
		}
		std::cout << "wrote " << raw.size() << " frames to " << aOut.getValue() << "\n";
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-kitti-video: error: " << e.what() << "\n";
		return 1;
	}
}
