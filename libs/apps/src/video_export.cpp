// --video FILE.mp4: the run drawn step by step with OpenCV (run_outputs.h). Headless.
#include <dynslam/apps/run_outputs.h>
#include <dynslam/landmark_ids.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
const cv::Scalar kTruth(0, 160, 0), kWhite(255, 255, 255), kGrey(150, 150, 150), kRed(40, 40, 220),
    kBlack(0, 0, 0);

cv::Scalar bgr(const TDrawnRun& r)
{
	return {double(r.rgb[2]), double(r.rgb[1]), double(r.rgb[0])};
}

/** World (x right, y up) to pixels, equal aspect, fitted into the frame. */
struct TView
{
	double cx = 0, cy = 0, scale = 1;
	int w = 0, h = 0;
	cv::Point px(const Eigen::Vector2d& p) const
	{
		return {int(std::lround(w / 2.0 + (p.x() - cx) * scale)),
		        int(std::lround(h / 2.0 - (p.y() - cy) * scale))};
	}
};

TView makeView(const std::vector<Eigen::Vector2d>& pts, int w, int h)
{
	double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
	for (const auto& p : pts)
		if (p.allFinite())
		{
			xmin = std::min(xmin, p.x());
			xmax = std::max(xmax, p.x());
			ymin = std::min(ymin, p.y());
			ymax = std::max(ymax, p.y());
		}
	TView v;
	v.w = w;
	v.h = h;
	if (!(xmin <= xmax)) return v;
	const double margin = 0.05 * std::max({xmax - xmin, ymax - ymin, 1.0});
	xmin -= margin, xmax += margin, ymin -= margin, ymax += margin;
	v.cx = 0.5 * (xmin + xmax);
	v.cy = 0.5 * (ymin + ymax);
	v.scale = std::min(double(w) / (xmax - xmin), double(h - 40) / (ymax - ymin));
	return v;
}

void drawEllipse(cv::Mat& img, const TView& v, const Eigen::Vector2d& at,
                 const Eigen::Matrix2d& cov, const cv::Scalar& c)
{
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (cov + cov.transpose()));
	if (es.info() != Eigen::Success) return;
	const Eigen::Vector2d ev = es.eigenvalues().cwiseMax(0.0);
	const Eigen::Vector2d ax = es.eigenvectors().col(1);
	const double a = 3.0 * std::sqrt(ev(1)) * v.scale, b = 3.0 * std::sqrt(ev(0)) * v.scale;
	const double angle = -std::atan2(ax.y(), ax.x()) * 180.0 / M_PI;  // image y points down
	cv::ellipse(img, v.px(at), cv::Size(std::max(1, int(a)), std::max(1, int(b))), angle, 0, 360, c,
	            1, cv::LINE_AA);
}

void drawReadings(cv::Mat& img, const TView& v, const Eigen::Vector3d& pose,
                  const mrpt::obs::CSensoryFrame::Ptr& sf)
{
	if (!sf) return;
	const auto obs = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	if (!obs) return;
	const auto& s = obs->sensorLocationOnRobot;
	const double c = std::cos(pose.z()), sn = std::sin(pose.z());
	const Eigen::Vector2d sensor =
	    pose.head<2>() + Eigen::Vector2d(c * s.x() - sn * s.y(), sn * s.x() + c * s.y());
	const double yaw0 = pose.z() + s.yaw();
	for (const auto& m : obs->sensedData)
	{
		const double a = yaw0 + m.yaw;
		const Eigen::Vector2d p = sensor + m.range * Eigen::Vector2d(std::cos(a), std::sin(a));
		const cv::Scalar col = ids::isStatic(m.landmarkID) ? kGrey : kRed;
		cv::line(img, v.px(sensor), v.px(p), col, 1, cv::LINE_AA);
		cv::circle(img, v.px(p), 3, col, -1, cv::LINE_AA);
	}
}
}  // namespace

void writeVideo(const std::string& path, const std::vector<TDrawnRun>& runs, const TGroundTruth* gt,
                const std::vector<mrpt::obs::CSensoryFrame::Ptr>& frames, double fps, int width,
                int height)
{
	if (runs.empty() || !runs.front().run) throw std::invalid_argument("writeVideo: no run");
	// The folder of the file (checked by checkOutputFile before the run).
	if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty())
		makeOutputDir(parent.string());
	std::vector<Eigen::Vector2d> extent;
	if (gt)
	{
		for (const auto& p : gt->ego) extent.push_back(p.head<2>());
		for (const auto& [id, p] : gt->landmarks) extent.push_back(p);
	}
	else
		for (const auto& e : runs.front().run->est.ego) extent.push_back(e.mean.head<2>());
	const TView view = makeView(extent, width, height);

	// Background: the ground truth.
	cv::Mat background(height, width, CV_8UC3, kWhite);
	if (gt)
	{
		for (size_t k = 1; k < gt->ego.size(); ++k)
			cv::line(background, view.px(gt->ego[k - 1].head<2>()), view.px(gt->ego[k].head<2>()),
			         kTruth, 1, cv::LINE_AA);
		for (const auto& [id, p] : gt->landmarks)
			cv::drawMarker(background, view.px(p), kTruth, cv::MARKER_CROSS, 6, 1);
	}

	cv::VideoWriter w(path, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps,
	                  cv::Size(width, height));
	if (!w.isOpened())
		throw std::runtime_error("cannot write the video '" + path +
		                         "' (OpenCV VideoWriter with codec mp4v could not open it)");
	const size_t n = runs.front().run->est.ego.size();
	std::vector<std::vector<Eigen::Vector3d>> paths(runs.size());
	for (size_t i = 0; i < runs.size(); ++i)
	{
		paths[i].assign(n, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
		for (const auto& e : runs[i].run->est.ego)
			if (e.step >= 0 && size_t(e.step) < n) paths[i][size_t(e.step)] = e.mean;
	}
	for (size_t k = 0; k < n; ++k)
	{
		cv::Mat img = background.clone();
		if (k < frames.size() && paths[0][k].allFinite())
			drawReadings(img, view, paths[0][k], frames[k]);
		for (size_t i = 0; i < runs.size(); ++i)
		{
			const cv::Scalar c = bgr(runs[i]);
			for (size_t j = 1; j <= k; ++j)
				if (paths[i][j - 1].allFinite() && paths[i][j].allFinite())
					cv::line(img, view.px(paths[i][j - 1].head<2>()),
					         view.px(paths[i][j].head<2>()), c, 2, cv::LINE_AA);
			for (const auto& e : runs[i].run->est.ego)
				if (e.step == int(k) && e.mean.allFinite())
					drawEllipse(img, view, e.mean.head<2>(), e.cov.topLeftCorner<2, 2>(), c);
			cv::putText(img, runs[i].name, cv::Point(10, 20 + 18 * int(i)),
			            cv::FONT_HERSHEY_SIMPLEX, 0.5, c, 1, cv::LINE_AA);
		}
		const std::string label = "step " + std::to_string(k) + "/" + std::to_string(n - 1) +
		                          (gt ? "   green: ground truth" : "");
		cv::putText(img, label, cv::Point(10, height - 12), cv::FONT_HERSHEY_SIMPLEX, 0.5, kBlack,
		            1, cv::LINE_AA);
		w.write(img);
	}
	w.release();
}
}  // namespace dynslam::apps
