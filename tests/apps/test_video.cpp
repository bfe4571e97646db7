/** writeVideo (run_outputs.h; issue 30 items 6 and 10): the view follows the ego with a window
 * of `window` metres (1 km in 960 pixels was unreadable), or shows the whole scene with 0. */
#include <apps_test_utils.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/run_outputs.h>

#include <opencv2/videoio.hpp>

using namespace dynslam;
using namespace dynslam::apps;

namespace
{
/** The ego drives 1 km along y = 0 in 101 steps; the filter's estimate is the truth. */
TFilterRun straightRun(io::TGroundTruth& gt)
{
	TFilterRun run;
	run.name = "dynamic";
	for (int k = 0; k <= 100; ++k)
	{
		gt.t.push_back(k);
		gt.ego.emplace_back(10.0 * k, 0.0, 0.0);
		eval::TEgoEstimate e;
		e.step = k;
		e.mean = gt.ego.back();
		e.cov = 1e-4 * Eigen::Matrix3d::Identity();
		run.est.ego.push_back(e);
	}
	gt.landmarks[0] = Eigen::Vector2d(500, 30);
	run.steps = 101;
	return run;
}

/** Frame k of the video. */
cv::Mat frame(const std::string& path, int k)
{
	cv::VideoCapture cap(path);
	cv::Mat f;
	for (int i = 0; i <= k; ++i)
		if (!cap.read(f)) return {};
	return f.clone();
}

/** Whether the pixel (x, y) is the filter's blue (after mp4v compression). */
bool blue(const cv::Mat& f, int x, int y)
{
	const auto p = f.at<cv::Vec3b>(y, x);  // BGR
	return p[0] > 150 && p[1] < 110 && p[2] < 110;
}
}  // namespace

TEST(Video, FollowsTheEgoWithAWindowOrShowsTheWholeScene)
{
	io::TGroundTruth gt;
	const TFilterRun run = straightRun(gt);
	const std::vector<TDrawnRun> drawn{{"dynamic", {0, 0, 255}, &run}};
	const std::string dir = apps_test::freshDir("video");
	writeVideo(dir + "/follow.mp4", drawn, &gt, {}, 10.0, 960, 540, 100.0);
	writeVideo(dir + "/whole.mp4", drawn, &gt, {}, 10.0, 960, 540, 0.0);
	for (int k : {10, 60})
	{
		const cv::Mat f = frame(dir + "/follow.mp4", k), w = frame(dir + "/whole.mp4", k);
		ASSERT_FALSE(f.empty());
		ASSERT_FALSE(w.empty());
		// Following: the path so far ends at the centre of the frame, and 30 m behind it (the
		// window is 100 m in 960 px) it is still drawn.
		EXPECT_TRUE(blue(f, 480 - 6, 270)) << "frame " << k;
		EXPECT_TRUE(blue(f, 480 - 288, 270)) << "frame " << k;
		EXPECT_FALSE(blue(f, 480 + 30, 270)) << "frame " << k;  // not ahead of the ego
	}
	// The whole scene: at step 10 the ego is at 10 % of the road, far left of the centre.
	const cv::Mat w = frame(dir + "/whole.mp4", 10);
	EXPECT_FALSE(blue(w, 480, 270));
	EXPECT_THROW(writeVideo(dir + "/bad.mp4", drawn, &gt, {}, 10.0, 960, 540, -1.0),
	             std::invalid_argument);
}
