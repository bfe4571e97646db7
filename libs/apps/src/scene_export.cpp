// --scene FILE.3Dscene: the run as an mrpt::opengl::COpenGLScene (run_outputs.h).
#include <dynslam/apps/run_outputs.h>
#include <mrpt/opengl/CEllipsoid2D.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CText.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
using mrpt::opengl::CEllipsoid2D;
using mrpt::opengl::CPointCloud;
using mrpt::opengl::CSetOfLines;

const mrpt::img::TColor kSceneTruth(0, 160, 0);

mrpt::img::TColor colorOf(const TDrawnRun& r) { return {r.rgb[0], r.rgb[1], r.rgb[2]}; }

CSetOfLines::Ptr strip(const std::vector<Eigen::Vector2d>& pts, const mrpt::img::TColor& c,
                       const std::string& name, float z, float width)
{
	auto l = CSetOfLines::Create();
	l->setName(name);
	l->setColor_u8(c);
	l->setLineWidth(width);
	for (size_t i = 1; i < pts.size(); ++i)
		if (pts[i - 1].allFinite() && pts[i].allFinite())
			l->appendLine(pts[i - 1].x(), pts[i - 1].y(), z, pts[i].x(), pts[i].y(), z);
	return l;
}

CEllipsoid2D::Ptr ellipse(const Eigen::Vector2d& at, const Eigen::Matrix2d& cov,
                          const mrpt::img::TColor& c, const std::string& name, float z)
{
	auto e = CEllipsoid2D::Create();
	e->setName(name);
	e->setColor_u8(c);
	e->setQuantiles(3.0f);
	e->setCovMatrix(mrpt::math::CMatrixDouble22(cov));
	e->setLocation(at.x(), at.y(), z);
	return e;
}

void addGroundTruth(mrpt::opengl::COpenGLScene& scene, const io::TGroundTruth& gt)
{
	std::vector<Eigen::Vector2d> path;
	for (const auto& p : gt.ego) path.push_back(p.head<2>());
	scene.insert(strip(path, kSceneTruth, "ground_truth/ego_path", 0.0f, 2.0f));
	auto lm = CPointCloud::Create();
	lm->setName("ground_truth/landmarks");
	lm->setColor_u8(kSceneTruth);
	lm->setPointSize(6.0f);
	for (const auto& [id, p] : gt.landmarks) lm->insertPoint(float(p.x()), float(p.y()), 0.0f);
	scene.insert(lm);
	for (const auto& o : gt.objects)
		for (Eigen::Index f = 0; f < o.num_features; ++f)
		{
			std::vector<Eigen::Vector2d> track;
			for (const auto& F : o.features) track.push_back(F.col(f));
			scene.insert(strip(
			    track, kSceneTruth,
			    "ground_truth/object_" + std::to_string(o.object) + "_feature_" + std::to_string(f),
			    0.0f, 1.0f));
		}
}

void addRun(mrpt::opengl::COpenGLScene& scene, const TDrawnRun& r, size_t every, float z)
{
	const auto& est = r.run->est;
	const auto c = colorOf(r);
	std::vector<const eval::TEgoEstimate*> ego;
	for (const auto& e : est.ego) ego.push_back(&e);
	std::sort(ego.begin(), ego.end(), [](auto a, auto b) { return a->step < b->step; });
	std::vector<Eigen::Vector2d> path;
	for (const auto* e : ego) path.push_back(e->mean.head<2>());
	scene.insert(strip(path, c, r.name + "/ego_path", z, 2.0f));
	for (size_t i = 0; i < ego.size(); ++i)
		if (i % std::max<size_t>(every, 1) == 0 || i + 1 == ego.size())
			scene.insert(ellipse(ego[i]->mean.head<2>(), ego[i]->cov.topLeftCorner<2, 2>(), c,
			                     r.name + "/ego_ellipse_" + std::to_string(ego[i]->step), z));
	auto lm = CPointCloud::Create();
	lm->setName(r.name + "/landmarks");
	lm->setColor_u8(c);
	lm->setPointSize(4.0f);
	for (const auto& l : est.landmarks)
	{
		lm->insertPoint(float(l.mean.x()), float(l.mean.y()), z);
		scene.insert(ellipse(l.mean, l.cov, c, r.name + "/landmark_" + std::to_string(l.id), z));
	}
	scene.insert(lm);
	// Object tracks: centroid of the time-0 features moved by the pose's translation (a
	// rotation about the time-0 centroid leaves the centroid in place, object_pose.h).
	std::map<int32_t, Eigen::Vector2d> c0;
	std::map<int32_t, int> nf;
	for (const auto& f : est.object_features)
	{
		c0.try_emplace(f.object, Eigen::Vector2d::Zero());
		c0[f.object] += f.mean;
		++nf[f.object];
	}
	std::map<int32_t, std::vector<const eval::TObjectPoseEstimate*>> poses;
	for (const auto& p : est.object_poses) poses[p.object].push_back(&p);
	for (auto& [obj, v] : poses)
	{
		if (!c0.count(obj)) continue;
		const Eigen::Vector2d base = c0[obj] / double(nf[obj]);
		std::sort(v.begin(), v.end(), [](auto a, auto b) { return a->step < b->step; });
		std::vector<Eigen::Vector2d> track;
		const std::string name = r.name + "/object_" + std::to_string(obj);
		for (size_t i = 0; i < v.size(); ++i)
		{
			const Eigen::Vector2d at = base + v[i]->mean.head<2>();
			track.push_back(at);
			if (i % std::max<size_t>(every, 1) == 0 || i + 1 == v.size())
				scene.insert(ellipse(at, v[i]->cov.topLeftCorner<2, 2>(), c,
				                     name + "_ellipse_" + std::to_string(v[i]->step), z));
		}
		scene.insert(strip(track, c, name + "_track", z, 1.5f));
	}
}
}  // namespace

/** The main viewport's camera (serialised with the scene) looks down on the centre of the data
 * from far enough to see all of it; a legend of 3-D texts (objects "legend/<name>") in each
 * filter's colour sits above the top-left corner of the data. */
static void frameAndLabel(mrpt::opengl::COpenGLScene& scene, const std::vector<TDrawnRun>& runs,
                          bool withTruth, double xmin, double xmax, double ymin, double ymax)
{
	const double extent = std::max({xmax - xmin, ymax - ymin, 10.0});
	auto& cam = scene.getViewport()->getCamera();
	cam.setPointingAt(float(0.5 * (xmin + xmax)), float(0.5 * (ymin + ymax)), 0.0f);
	cam.setZoomDistance(float(1.2 * extent));
	cam.setElevationDegrees(70.0f);
	cam.setAzimuthDegrees(-90.0f);
	std::vector<std::pair<std::string, mrpt::img::TColor>> entries;
	if (withTruth) entries.emplace_back("ground truth", mrpt::img::TColor(0, 160, 0));
	for (const auto& r : runs)
		entries.emplace_back(r.name, mrpt::img::TColor(r.rgb[0], r.rgb[1], r.rgb[2]));
	const double line = 0.03 * extent;
	for (size_t i = 0; i < entries.size(); ++i)
	{
		auto t = mrpt::opengl::CText::Create(entries[i].first);
		t->setName("legend/" + entries[i].first);
		t->setLocation(xmin, ymax + line * double(entries.size() - i), 0.0);
		t->setColor_u8(entries[i].second);
		scene.insert(t);
	}
}

void writeScene(const std::string& path, const std::vector<TDrawnRun>& runs,
                const io::TGroundTruth* gt, size_t ellipseEvery)
{
	// The folder of the file (checked by checkOutputFile before the run).
	if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty())
		makeOutputDir(parent.string());
	mrpt::opengl::COpenGLScene scene;
	double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
	auto grow = [&](const Eigen::Vector2d& p)
	{
		if (!p.allFinite()) return;
		xmin = std::min(xmin, p.x());
		xmax = std::max(xmax, p.x());
		ymin = std::min(ymin, p.y());
		ymax = std::max(ymax, p.y());
	};
	if (gt)
		for (const auto& p : gt->ego) grow(p.head<2>());
	else
		for (const auto& r : runs)
			if (r.run)
				for (const auto& e : r.run->est.ego) grow(e.mean.head<2>());
	if (xmin <= xmax)
	{
		auto grid = mrpt::opengl::CGridPlaneXY::Create(
		    float(std::floor(xmin / 10) * 10 - 50), float(std::ceil(xmax / 10) * 10 + 50),
		    float(std::floor(ymin / 10) * 10 - 50), float(std::ceil(ymax / 10) * 10 + 50), -0.05f,
		    10.0f);
		grid->setName("grid");
		grid->setColor_u8(200, 200, 200);
		scene.insert(grid);
	}
	if (gt) addGroundTruth(scene, *gt);
	for (size_t i = 0; i < runs.size(); ++i)
		if (runs[i].run) addRun(scene, runs[i], ellipseEvery, 0.02f * float(i + 1));
	if (xmin <= xmax) frameAndLabel(scene, runs, gt != nullptr, xmin, xmax, ymin, ymax);
	if (!scene.saveToFile(path))
		throw std::runtime_error("cannot write the scene file '" + path + "'");
}
}  // namespace dynslam::apps
