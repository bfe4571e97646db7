#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/classify.h>
#include <dynslam/kitti/geometry.h>
#include <dynslam/kitti/import.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "import_detail.h"

namespace dynslam::kitti
{
namespace
{
void checkOptions(const TImportOptions& o)
{
	auto need = [](bool ok, const std::string& what)
	{
		if (!ok) throw std::invalid_argument("kitti import options: " + what);
	};
	need(o.dt > 0 && std::isfinite(o.dt), "dt must be > 0");
	need(o.max_range > 0 && std::isfinite(o.max_range), "max_range must be > 0");
	need(o.fov_deg > 0 && o.fov_deg <= 360, "fov_deg must be in (0, 360]");
	need(o.static_radius >= 0 && std::isfinite(o.static_radius), "static_radius must be >= 0");
	need(o.std_range > 0 && o.std_bearing > 0, "std_range and std_bearing must be > 0");
	need(o.odo_std_xy > 0 && o.odo_std_phi > 0, "odo_std_xy and odo_std_phi must be > 0");
	need(o.odo_std_xy_per_m >= 0 && o.odo_std_phi_per_m >= 0, "odo_std_*_per_m must be >= 0");
	need(o.pose_scale > 0 && std::isfinite(o.pose_scale), "pose_scale must be > 0");
}

/** Tracks, their classification and which boxes are read. */
void buildTracks(const TKittiLabels& L, const std::vector<Eigen::Vector3d>& ego,
                 const TImportOptions& o, TImportResult& res, std::vector<uint8_t>& read)
{
	auto& s = res.summary;
	read.assign(L.boxes.size(), 0);
	const double halfFov = o.fov_deg * M_PI / 360.0;
	for (size_t i = 0; i < L.boxes.size(); ++i)
	{
		const TKittiBox& b = L.boxes[i];
		TTrack& t = res.tracks[b.track];
		if (t.track < 0)
		{
			t.track = b.track;
			t.type = b.type;
			t.length = b.l;
			t.width = b.w;
		}
		t.boxes.push_back(i);
		const Eigen::Vector2d rb = rangeBearing(boxCentreEgo(b));
		if (rb.x() > o.max_range)
			++s.out_of_range;
		else if (std::abs(rb.y()) > halfFov)
			++s.out_of_fov;
		else
			read[i] = 1;
	}
	for (auto& [id, t] : res.tracks)
	{
		std::sort(t.boxes.begin(), t.boxes.end(),
		          [&](size_t a, size_t b) { return L.boxes[a].frame < L.boxes[b].frame; });
		std::vector<Eigen::Vector2d> centres;
		for (size_t i : t.boxes)
		{
			const TKittiBox& b = L.boxes[i];
			centres.push_back(egoToWorld(ego[size_t(b.frame)], boxCentreEgo(b)));
			if (read[i] && t.first_read < 0) t.first_read = b.frame;
			t.read_frames += read[i];
		}
		t.frames = t.boxes.size();
		t.first_frame = L.boxes[t.boxes.front()].frame;
		t.last_frame = L.boxes[t.boxes.back()].frame;
		t.radius = footprintRadius(centres);
		t.moving = isMoving(t.radius, o.static_radius);
	}
}

/** Object indices of the moving tracks that are read; the reading IDs of every corner. */
std::map<std::pair<int, int>, int32_t> assignIds(TImportResult& res, const TImportOptions& o)
{
	std::vector<TTrack*> movers;
	for (auto& [id, t] : res.tracks)
		if (t.moving && t.first_read >= 0) movers.push_back(&t);
	std::stable_sort(movers.begin(), movers.end(),
	                 [](const TTrack* a, const TTrack* b)
	                 { return a->first_read < b->first_read; });
	for (size_t i = 0; i < movers.size(); ++i) movers[i]->object = int(i);

	std::map<std::pair<int, int>, int32_t> ids;  // (track, corner) -> ID
	std::vector<std::pair<int, int>> corners;
	for (const auto& [id, t] : res.tracks)
		if (t.first_read >= 0)
			for (int c = 0; c < 4; ++c) corners.emplace_back(t.track, c);
	if (o.anonymous)
	{
		std::vector<int32_t> perm(corners.size());
		std::iota(perm.begin(), perm.end(), 0);
		std::mt19937 rng(o.seed + 7919u);
		std::shuffle(perm.begin(), perm.end(), rng);
		for (size_t i = 0; i < corners.size(); ++i) ids[corners[i]] = perm[i];
	}
	else
		for (const auto& tc : corners)
		{
			const TTrack& t = res.tracks.at(tc.first);
			if (t.moving)
				ids[tc] = ids::objectFeatureId(t.object, tc.second);
			else if (t.track > (ids::kStaticMax - 3) / 4)
				throw std::runtime_error("track " + std::to_string(t.track) +
				                         ": too large for the static ID range (4 track + corner)");
			else
				ids[tc] = 4 * t.track + tc.second;
		}
	for (const auto& [tc, id] : ids)
		res.ids.push_back({id, tc.first, tc.second, res.tracks.at(tc.first).moving});
	std::sort(res.ids.begin(), res.ids.end(),
	          [](const TIdRow& a, const TIdRow& b) { return a.id < b.id; });
	return ids;
}

Eigen::Matrix3d odometryCov(const Eigen::Vector3d& inc, const TImportOptions& o)
{
	const double d = inc.head<2>().norm();
	const double sxy = o.odo_std_xy + o.odo_std_xy_per_m * d;
	const double sphi = o.odo_std_phi + o.odo_std_phi_per_m * d;
	return Eigen::Vector3d(sxy * sxy, sxy * sxy, sphi * sphi).asDiagonal();
}

void buildSteps(const TKittiLabels& L, const std::vector<Eigen::Vector3d>& ego,
                const std::vector<uint8_t>& read, const std::map<std::pair<int, int>, int32_t>& ids,
                const TImportOptions& o, TImportResult& res)
{
	std::vector<std::vector<size_t>> byFrame(ego.size());
	for (size_t i = 0; i < L.boxes.size(); ++i)
		if (read[i]) byFrame[size_t(L.boxes[i].frame)].push_back(i);
	std::mt19937 rng(o.seed);
	std::normal_distribution<double> N01(0.0, 1.0);
	res.steps.resize(ego.size());
	for (size_t k = 0; k < ego.size(); ++k)
	{
		TStep& s = res.steps[k];
		s.t = double(k) * o.dt;
		if (k > 0)
		{
			const Eigen::Vector3d exact = models::poseDifference(ego[k], ego[k - 1]);
			s.cov = odometryCov(exact, o);
			s.increment = exact;
			if (o.odometry_noise == ENoise::Gaussian)
				for (int j = 0; j < 3; ++j) s.increment[j] += std::sqrt(s.cov(j, j)) * N01(rng);
			s.increment.z() = models::wrapToPi(s.increment.z());
			res.summary.path_length += exact.head<2>().norm();
		}
		for (size_t i : byFrame[k])
		{
			const TKittiBox& b = L.boxes[i];
			const auto corners = footprintCornersEgo(b);
			for (int c = 0; c < 4; ++c)
			{
				Eigen::Vector2d z = rangeBearing(corners.col(c));
				if (o.noise == ENoise::Gaussian)
				{
					z.x() += o.std_range * N01(rng);
					z.y() = models::wrapToPi(z.y() + o.std_bearing * N01(rng));
				}
				s.readings.push_back({ids.at({b.track, c}), z.x(), z.y(), b.track, c});
			}
			++res.summary.boxes_read;
			res.summary.readings += 4;
		}
	}
}
}  // namespace

TImportResult importSequence(const std::vector<TCameraPose>& poses, const TKittiLabels& labels,
                             const TImportOptions& opts, const std::string& sequence)
{
	checkOptions(opts);
	if (poses.empty()) throw std::runtime_error("kitti import: no poses");
	checkLabelsAgainstPoses(labels, poses.size(), "the pose file");
	if (opts.pose_scale_auto)
	{
		TImportOptions at1 = opts;
		at1.pose_scale_auto = false;
		at1.pose_scale = 1;
		const double fit = importSequence(poses, labels, at1, sequence).summary.trajectory_scale;
		at1.pose_scale = std::isfinite(fit) && fit > 0 ? 1 / fit : 1.0;
		TImportResult res = importSequence(poses, labels, at1, sequence);
		res.summary.pose_scale_auto = true;
		res.summary.trajectory_scale_unscaled = fit;
		return res;
	}
	TImportResult res;
	auto& s = res.summary;
	s.pose_scale = opts.pose_scale;
	s.sequence = sequence;
	s.steps = poses.size();
	s.label_rows = labels.rows;
	s.dontcare = labels.dontcare;
	s.no3d = labels.no3d;
	s.boxes = labels.boxes.size();
	s.types = labels.types;
	s.unknown_types = labels.unknown_types;
	std::vector<Eigen::Vector3d> ego;
	ego.reserve(poses.size());
	for (const auto& T : poses)
	{
		ego.push_back(egoPoseFromCamera(T));
		ego.back().head<2>() *= opts.pose_scale;
	}
	std::vector<uint8_t> read;
	buildTracks(labels, ego, opts, res, read);
	const auto ids = assignIds(res, opts);
	buildSteps(labels, ego, read, ids, opts, res);
	detail::fillGroundTruth(labels, ego, read, ids, opts, res);
	s.tracks = res.tracks.size();
	for (const auto& [id, t] : res.tracks)
	{
		(t.moving ? s.moving_tracks : s.static_tracks)++;
		if (t.first_read < 0) ++s.tracks_never_read;
	}
	return res;
}

namespace
{
std::string numberText(double v)
{
	std::ostringstream o;
	o << v;
	return o.str();
}

std::string countsText(const std::map<std::string, size_t>& m)
{
	if (m.empty()) return " none";
	std::string s;
	for (const auto& [k, n] : m) s += " " + k + " " + std::to_string(n) + ",";
	s.pop_back();
	return s;
}
}  // namespace

std::string TImportSummary::toText() const
{
	std::ostringstream o;
	o << "KITTI tracking sequence " << sequence << ": " << steps << " steps (frames), ego path "
	  << path_length << " m\n"
	  << "  label lines " << label_rows << ": DontCare " << dontcare << " (skipped), no 3-D data "
	  << no3d << " (skipped), boxes " << boxes << "\n"
	  << "  boxes read " << boxes_read << ", out of range " << out_of_range
	  << ", out of field of view " << out_of_fov << "; readings (4 corners per box) " << readings
	  << "\n"
	  << "  tracks " << tracks << ": static " << static_tracks << ", moving " << moving_tracks
	  << ", never read " << tracks_never_read << "\n"
	  << "  label lines per type:" << countsText(types) << "\n"
	  << "  types that are not KITTI types (kept as boxes):" << countsText(unknown_types) << "\n"
	  << "  annotation jitter (static tracks, read): frame-to-frame motion rms " << floor_trans_rmse
	  << " m, " << floor_rot_rmse << " rad (" << floor_n << " motions); corners about their mean "
	  << static_corner_rms << " m rms\n"
	  << "  trajectory / labels scale (static tracks, diagnostic) " << trajectory_scale << "\n"
	  << "  trajectory positions scaled by " << pose_scale
	  << (pose_scale_auto ? " (pose_scale = auto: 1 / the diagnostic at scale 1, " +
	                            numberText(trajectory_scale_unscaled) + ")"
	                      : " (pose_scale)")
	  << "\n"
	  << detections_text;
	return o.str();
}
}  // namespace dynslam::kitti
