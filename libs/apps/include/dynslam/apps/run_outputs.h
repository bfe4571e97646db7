#pragma once
/** @file run_outputs.h
 * Optional outputs of the run apps (dynslam-run, dynslam-compare) and helpers around them:
 *  - the output folder with a readable error;
 *  - the time-base check between the rawlog and the ground truth;
 *  - the reference for comparing filters without ground truth;
 *  - --scene FILE.3Dscene: an mrpt::opengl::COpenGLScene for MRPT's SceneViewer3D;
 *  - --video FILE.mp4: the run drawn step by step (OpenCV VideoWriter, headless).
 * See doc/apps.md. */
#include <dynslam/apps/filter_run.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace dynslam::apps
{
/** Creates `dir` (and its parents). Throws std::runtime_error with a sentence naming the
 * folder and the reason (e.g. "cannot create the output folder 'a/b': 'a' is a file, not a
 * folder") instead of a raw std::filesystem error. */
void makeOutputDir(const std::string& dir);

/** Checks, creating nothing, that makeOutputDir(dir) can succeed: `dir` is a writable folder, or
 * its nearest existing ancestor is a writable folder (no file in the way). Throws
 * std::runtime_error with makeOutputDir's sentences. Every app calls it before reading its
 * inputs, so that a bad input leaves no output folder behind. */
void checkOutputDirUsable(const std::string& dir);

/** Checks, creating nothing, an output file given on the command line (`flag`, e.g.
 * "--video"): not a folder, its folder usable (checkOutputDirUsable; created when the file is
 * written), and, if `extensions` is not empty, one of them (case-insensitive). Empty `path`:
 * nothing asked, nothing checked. Throws std::runtime_error naming the flag and the path. */
void checkOutputFile(const std::string& path, const std::string& flag,
                     const std::vector<std::string>& extensions = {});

/** The video extensions writeVideo's codec (mp4v) can be written in. */
const std::vector<std::string>& videoExtensions();

/** Empty if the ego time stamps of `run` (the rawlog's) equal gt.t at every step within
 * 1 ms (or if either is missing); otherwise a warning naming the first differing step, since
 * trajectory.tum and the ground truth's BASE_gt_ego.tum would then not be associated by evo. */
std::string timeBaseWarning(const TFilterRun& run, const io::TGroundTruth& gt);

/** A run's estimates as a ground truth (ego per step, final landmarks; no objects), to
 * score the other filters against it when there is no ground truth: the "errors" are then
 * differences between filters, not errors. */
io::TGroundTruth estimatesAsReference(const TFilterRun& run);

/** One filter in a scene or video. */
struct TDrawnRun
{
	std::string name;
	std::array<uint8_t, 3> rgb{0, 0, 255};
	const TFilterRun* run = nullptr;
};

/** Writes an mrpt::opengl::COpenGLScene (COpenGLScene::saveToFile) with, per filter: the ego
 * path (line strip), 3-sigma ego ellipses every `ellipseEvery` steps and at the last step, the
 * final landmarks with 3-sigma ellipses, each object's track (centroid of its time-0 feature
 * estimates moved by the estimated pose translation) with 3-sigma ellipses of the translation;
 * the ground truth (if given) in green: ego path, landmarks, object feature tracks; a ground
 * grid. Object names: "<filter>/ego_path", ".../landmarks", "ground_truth/..." (for tests).
 * Throws std::runtime_error naming the file if it cannot be written. */
void writeScene(const std::string& path, const std::vector<TDrawnRun>& runs,
                const io::TGroundTruth* gt, size_t ellipseEvery = 10);

/** Writes the run drawn step by step, one frame per step (MPEG-4 part 2, fourcc mp4v, in an
 * .mp4 container; OpenCV VideoWriter, no window): top view of the ground truth (green: ego
 * path, landmarks, the objects' tracks so far), each filter's ego path so far with its 3-sigma
 * ellipse and its objects' tracks (dots, the current pose larger), and the readings of that step
 * drawn from the first filter's pose (static landmarks grey, object features red), a scale bar.
 * The view follows the first filter's ego (the truth's where it has none) with a window
 * `window` metres wide, equal axes, and a small overview of the whole path with the window
 * marked; window = 0, or a window wider than the whole scene: the whole scene, fixed.
 * Throws std::runtime_error naming the file if the writer cannot be opened, and
 * std::invalid_argument on a negative window. */
void writeVideo(const std::string& path, const std::vector<TDrawnRun>& runs,
                const io::TGroundTruth* gt,
                const std::vector<mrpt::obs::CSensoryFrame::Ptr>& frames, double fps = 10.0,
                int width = 960, int height = 540, double window = 120.0);
}  // namespace dynslam::apps
