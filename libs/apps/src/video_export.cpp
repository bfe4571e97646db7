// --video FILE.mp4: the run drawn step by step with OpenCV (run_outputs.h). Headless.
#include <dynslam/apps/run_outputs.h>
#include <dynslam/core/landmark_ids.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
const cv::Scalar kTruth(0, 160, 0), kLightTruth(170, 225, 170), kTruthObject(120, 200, 120),
    kWhite(255, 255, 255), kGrey(150, 150, 150), kRed(40, 40, 220), kBlack(0, 0, 0);
constexpr double kNaNd = std::numeric_limits<double>::quiet_NaN();

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

/** Truth per frame (the view moves): ego path so far dimmed ahead, landmarks, object tracks
 * (centroid of the true features) up to step k; only what lies near the view. */
void drawTruth(cv::Mat& img, const TView& v, const io::TGroundTruth& gt, size_t k)
{
	const double reach = 0.75 * std::hypot(v.w, v.h) / v.scale;
	auto near = [&](const Eigen::Vector2d& p)
	{ return p.allFinite() && std::abs(p.x() - v.cx) < reach && std::abs(p.y() - v.cy) < reach; };
	for (size_t j = 1; j < gt.ego.size(); ++j)
		if (near(gt.ego[j].head<2>()) || near(gt.ego[j - 1].head<2>()))
			cv::line(img, v.px(gt.ego[j - 1].head<2>()), v.px(gt.ego[j].head<2>()),
			         j <= k ? kTruth : kLightTruth, 1, cv::LINE_AA);
	for (const auto& [id, p] : gt.landmarks)
		if (near(p)) cv::drawMarker(img, v.px(p), kTruth, cv::MARKER_CROSS, 6, 1);
	for (const auto& o : gt.objects)
	{
		Eigen::Vector2d prev = Eigen::Vector2d::Constant(kNaNd);
		for (size_t j = 0; j <= k && j < o.features.size(); ++j)
		{
			const bool seen = o.features[j].cols() > 0;
			const Eigen::Vector2d c = seen ? Eigen::Vector2d(o.features[j].rowwise().mean()) : prev;
			if (seen && prev.allFinite() && (near(c) || near(prev)))
				cv::line(img, v.px(prev), v.px(c), kTruthObject, 1, cv::LINE_AA);
			prev = c;
		}
	}
}

/** Each estimated object's track (centroid of its time-0 features moved by xi) up to step k. */
void drawObjectEstimates(cv::Mat& img, const TView& v, const eval::TRunEstimates& est, size_t k,
                         const cv::Scalar& c)
{
	std::map<int32_t, Eigen::Vector2d> sum;
	std::map<int32_t, int> n;
	for (const auto& f : est.object_features)
	{
		sum.try_emplace(f.object, Eigen::Vector2d::Zero());
		sum[f.object] += f.mean;
		++n[f.object];
	}
	for (const auto& p : est.object_poses)
		if (p.step >= 0 && size_t(p.step) <= k && n.count(p.object))
			cv::circle(img, v.px(sum[p.object] / n[p.object] + p.mean.head<2>()),
			           size_t(p.step) == k ? 4 : 1, c, -1, cv::LINE_AA);
}

/** A scale bar (bottom right) and, when following, a small overview of the whole extent with the
 * followed window as a rectangle (top right). */
void drawScaleAndOverview(cv::Mat& img, const TView& v, const TView& whole,
                          const std::vector<Eigen::Vector2d>& extent, bool follow)
{
	const double nice[] = {1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000};
	double bar = nice[0];
	for (double b : nice)
		if (b * v.scale <= 0.2 * v.w) bar = b;
	const int x1 = v.w - 15, x0 = x1 - int(std::lround(bar * v.scale)), y = v.h - 15;
	cv::line(img, {x0, y}, {x1, y}, kBlack, 2);
	cv::putText(img, std::to_string(int(bar)) + " m", {x0, y - 6}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
	            kBlack, 1, cv::LINE_AA);
	if (!follow) return;
	const cv::Rect box(v.w - whole.w - 10, 10, whole.w, whole.h);
	cv::Mat roi = img(box);
	roi.setTo(kWhite);
	for (size_t j = 1; j < extent.size(); ++j)
		cv::line(roi, whole.px(extent[j - 1]), whole.px(extent[j]), kGrey, 1);
	const Eigen::Vector2d half(0.5 * v.w / v.scale, 0.5 * v.h / v.scale), c(v.cx, v.cy);
	cv::rectangle(roi, whole.px(c - half), whole.px(c + half), kBlack, 1);
	cv::rectangle(img, box, kGrey, 1);
}
}  // namespace

void writeVideo(const std::string& path, const std::vector<TDrawnRun>& runs,
                const io::TGroundTruth* gt,
                const std::vector<mrpt::obs::CSensoryFrame::Ptr>& frames, double fps, int width,
                int height, double window)
{
	if (runs.empty() || !runs.front().run) throw std::invalid_argument("writeVideo: no run");
	if (!(window >= 0) || !std::isfinite(window))
		throw std::invalid_argument("writeVideo: the window must be >= 0 metres (0: whole scene)");
	// The folder of the file (checked by checkOutputFile before the run).
	if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty())
		makeOutputDir(parent.string());
	std::vector<Eigen::Vector2d> extent;
	if (gt)
		for (const auto& p : gt->ego) extent.push_back(p.head<2>());
	else
		for (const auto& e : runs.front().run->est.ego) extent.push_back(e.mean.head<2>());
	std::vector<Eigen::Vector2d> all = extent;
	if (gt)
		for (const auto& [id, p] : gt->landmarks) all.push_back(p);
	const TView whole = makeView(all, width, height);
	const TView overview = makeView(extent, width / 4, std::max(60, height / 6));
	const bool follow = window > 0 && window * whole.scale < width;  // else it would zoom out

	cv::VideoWriter w(path, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps,
	                  cv::Size(width, height));
	if (!w.isOpened())
		throw std::runtime_error("cannot write the video '" + path +
		                         "' (OpenCV VideoWriter with codec mp4v could not open it)");
	const size_t n = runs.front().run->est.ego.size();
	std::vector<std::vector<Eigen::Vector3d>> paths(runs.size());
	for (size_t i = 0; i < runs.size(); ++i)
	{
		paths[i].assign(n, Eigen::Vector3d::Constant(kNaNd));
		for (const auto& e : runs[i].run->est.ego)
			if (e.step >= 0 && size_t(e.step) < n) paths[i][size_t(e.step)] = e.mean;
	}
	Eigen::Vector2d centre(whole.cx, whole.cy);
	for (size_t k = 0; k < n; ++k)
	{
		TView view = whole;
		if (follow)
		{
			// Centred on the first filter's ego (the truth's where it has none).
			if (paths[0][k].allFinite())
				centre = paths[0][k].head<2>();
			else if (gt && k < gt->ego.size())
				centre = gt->ego[k].head<2>();
			view.cx = centre.x(), view.cy = centre.y(), view.scale = width / window;
		}
		cv::Mat img(height, width, CV_8UC3, kWhite);
		if (gt) drawTruth(img, view, *gt, k);
		if (k < frames.size() && paths[0][k].allFinite())
			drawReadings(img, view, paths[0][k], frames[k]);
		for (size_t i = 0; i < runs.size(); ++i)
		{
			const cv::Scalar c = bgr(runs[i]);
			// Earlier filters wider, so that coinciding paths all stay visible (as the figures).
			const int lineWidth = std::min(8, 2 + 2 * int(runs.size() - 1 - i));
			drawObjectEstimates(img, view, runs[i].run->est, k, c);
			for (size_t j = 1; j <= k; ++j)
				if (paths[i][j - 1].allFinite() && paths[i][j].allFinite())
					cv::line(img, view.px(paths[i][j - 1].head<2>()),
					         view.px(paths[i][j].head<2>()), c, lineWidth, cv::LINE_AA);
			for (const auto& e : runs[i].run->est.ego)
				if (e.step == int(k) && e.mean.allFinite())
					drawEllipse(img, view, e.mean.head<2>(), e.cov.topLeftCorner<2, 2>(), c);
			cv::putText(img, runs[i].name, cv::Point(10, 20 + 18 * int(i)),
			            cv::FONT_HERSHEY_SIMPLEX, 0.5, c, 1, cv::LINE_AA);
		}
		drawScaleAndOverview(img, view, overview, extent, follow);
		const std::string label = "step " + std::to_string(k) + "/" + std::to_string(n - 1) +
		                          (gt ? "   green: ground truth" : "");
		cv::putText(img, label, cv::Point(10, height - 12), cv::FONT_HERSHEY_SIMPLEX, 0.5, kBlack,
		            1, cv::LINE_AA);
		w.write(img);
	}
	w.release();
}
}  // namespace dynslam::apps
