#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/box_router.h>

#include <cmath>
#include <map>
#include <stdexcept>

namespace dynslam::estimator
{
int32_t CBoxRouter::cornerId(int32_t track, int corner)
{
	constexpr int32_t kMaxTrack = (kFirstResolvedId - kFirstCornerId) / 4 - 1;
	if (track < 0 || track > kMaxTrack || corner < 0 || corner > 3)
		throw std::out_of_range("CBoxRouter::cornerId: track " + std::to_string(track) +
		                        ", corner " + std::to_string(corner) + " outside the ID space");
	return kFirstCornerId + 4 * track + corner;
}

std::array<int32_t, 4> CBoxRouter::cornerIds(int32_t track)
{
	return {cornerId(track, 0), cornerId(track, 1), cornerId(track, 2), cornerId(track, 3)};
}

std::vector<TWorldBox> CBoxRouter::placeBoxes(const std::vector<TBoxDetection>& boxes,
                                              std::map<int32_t, size_t>& boxOfGroup, int step)
{
	// The ego predicted by this step's odometry, then the sensor.
	m_placed = models::composePose(m_ctx.ego, m_ctx.u);
	const Eigen::Vector3d sensor = models::composePose(m_placed, m_ctx.sensor_pose);
	std::vector<TWorldBox> world(boxes.size());
	for (size_t b = 0; b < boxes.size(); ++b)
	{
		world[b].pose = models::composePose(sensor, boxes[b].pose);
		world[b].extent = boxes[b].extent;
		world[b].cls = boxes[b].cls;
		world[b].score = boxes[b].score;
		if (!boxOfGroup.emplace(boxes[b].group, b).second)
			throw std::runtime_error("feature_labels = boxes: step " + std::to_string(step) +
			                         ": box group " + std::to_string(boxes[b].group) + " twice");
	}
	return world;
}

namespace
{
TClassifyParams withHints(TClassifyParams p)
{
	p.use_hints = true;
	return p;
}
}  // namespace

CBoxRouter::CBoxRouter(const TBoxTrackerParams& tracker, TClassifyParams classify)
    : m_trackerParams(tracker), m_tracker(tracker), m_inner(withHints(std::move(classify)))
{
}

void CBoxRouter::validate(const std::vector<TReading>& readings, const std::string& who) const
{
	std::vector<TReading> rest;
	rest.reserve(readings.size());
	for (size_t i = 0; i < readings.size(); ++i)
	{
		const TReading& r = readings[i];
		if (r.id == -1 && r.hint >= 0) continue;  // a box corner
		if (r.id >= kFirstCornerId)
			throw std::runtime_error(who + ": measurement " + std::to_string(i) + " (ID " +
			                         std::to_string(r.id) +
			                         "): IDs >= 500000000 are reserved for box corners "
			                         "(feature_labels = boxes)");
		rest.push_back(r);
	}
	m_inner.validate(rest, who);
}

void CBoxRouter::setStaticAssociation(StaticAssociationFn f)
{
	m_inner.setStaticAssociation(std::move(f));
}

void CBoxRouter::setContext(const TRouterContext& ctx)
{
	m_ctx = ctx;
	m_inner.setContext(ctx);
}

TRoutedStep CBoxRouter::route(int step, const std::vector<TReading>& readings,
                              const std::function<bool(int32_t)>& isKnownStatic)
{
	static const std::string who = "feature_labels = boxes";
	const std::vector<TBoxDetection> none;
	const std::vector<TBoxDetection>& boxes = m_ctx.boxes ? *m_ctx.boxes : none;
	if (!boxes.empty() && !std::isfinite(m_ctx.stamp))
		throw std::runtime_error(who + ": step " + std::to_string(step) +
		                         " has detector boxes but no time stamp (the tracker's dt)");
	if (std::isfinite(m_ctx.stamp) && std::isfinite(m_lastStamp) && m_ctx.stamp > m_lastStamp)
		m_tracker.predict(m_ctx.stamp - m_lastStamp);
	if (std::isfinite(m_ctx.stamp)) m_lastStamp = m_ctx.stamp;

	std::map<int32_t, size_t> boxOfGroup;
	const std::vector<TWorldBox> world = placeBoxes(boxes, boxOfGroup, step);
	// The joint part: tracks the filter holds are predicted by the filter.
	if (m_ctx.box_prediction)
		for (const TBoxTrack& t : m_tracker.tracks())
		{
			Eigen::Vector2d c;
			Eigen::Matrix2d C;
			if (t.state != ETrackState::Tentative && m_ctx.box_prediction(cornerIds(t.id), c, C))
				m_tracker.overridePrediction(t.id, c, C);
		}
	const TBoxAssignment a = m_tracker.update(world);
	std::map<int32_t, ETrackState> state;
	for (const TBoxTrack& t : m_tracker.tracks()) state[t.id] = t.state;

	std::vector<TReading> out;
	out.reserve(readings.size());
	std::vector<int> corners(boxes.size(), 0);
	size_t skipped = 0;
	for (const TReading& r : readings)
	{
		if (!(r.id == -1 && r.hint >= 0))
		{
			out.push_back(r);
			continue;
		}
		const auto it = boxOfGroup.find(r.hint);
		if (it == boxOfGroup.end())
			throw std::runtime_error(who + ": step " + std::to_string(step) +
			                         ": a corner reading of group " + std::to_string(r.hint) +
			                         " that is not a box of the step");
		const size_t b = it->second;
		const int c = corners[b]++;
		if (c > 3)
			throw std::runtime_error(who + ": step " + std::to_string(step) + ": box group " +
			                         std::to_string(r.hint) + " has more than four corners");
		const int32_t track = a.track[b];
		const auto s = state.find(track);
		if (track < 0 || s == state.end() || s->second != ETrackState::Confirmed)
		{
			++skipped;
			continue;
		}
		TReading q = r;
		q.id = cornerId(track, (c + (a.flipped[b] ? 2 : 0)) % 4);
		q.hint = track;
		out.push_back(q);
	}
	for (size_t b = 0; b < boxes.size(); ++b)
		if (corners[b] != 4)
			throw std::runtime_error(who + ": step " + std::to_string(step) + ": box group " +
			                         std::to_string(boxes[b].group) + " has " +
			                         std::to_string(corners[b]) + " corner readings, not 4");
	TRoutedStep routed = m_inner.route(step, out, isKnownStatic);
	routed.skipped_box_corners = skipped;
	return routed;
}

int32_t CBoxRouter::featureId(int32_t object, int32_t feature) const
{
	return m_inner.featureId(object, feature);
}

void CBoxRouter::reset()
{
	m_tracker = CBoxTracker(m_trackerParams);
	m_inner.reset();
	m_lastStamp = std::numeric_limits<double>::quiet_NaN();
	m_placed.setZero();
}

void CBoxRouter::mergeObjects(int32_t from, int32_t into) { m_inner.mergeObjects(from, into); }

bool CBoxRouter::allowsMerge(int32_t a, int32_t b) const { return m_inner.allowsMerge(a, b); }
}  // namespace dynslam::estimator
