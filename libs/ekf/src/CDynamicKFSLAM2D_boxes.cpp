/** feature_labels = boxes (issue 31, doc/boxes.md): what the EKF gives the box router (the
 * joint prediction of a box whose corners are static landmarks of the state) and the tracks it
 * reports (trackedBoxes: where the filter holds the box, as a parked car's four landmarks or
 * as a moving object whose pose is of this step, its centre is the filter's; else the
 * tracker's). */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/box_router.h>
#include <dynslam/models/se2.h>

#include <map>

namespace dynslam
{
bool CDynamicKFSLAM2D::boxPrediction(const std::array<int32_t, 4>& ids, Eigen::Vector2d& c,
                                     Eigen::Matrix2d& C) const
{
	std::array<Eigen::Index, 4> k{};
	for (size_t i = 0; i < 4; ++i)
	{
		const auto it = m_staticBlock.find(ids[i]);
		if (it == m_staticBlock.end()) return false;
		k[i] = m_layout.first(it->second);
	}
	// The footprint centre is the mean of the four corners: c = A m, C = A P A^T with
	// A = [I/4 I/4 I/4 I/4] on the corners' blocks.
	const auto P = cov();
	c.setZero();
	C.setZero();
	for (size_t i = 0; i < 4; ++i)
	{
		c += 0.25 * Eigen::Vector2d(m_xkk[size_t(k[i])], m_xkk[size_t(k[i]) + 1]);
		for (size_t j = 0; j < 4; ++j) C += P.block(k[i], k[j], 2, 2) / 16.0;
	}
	return true;
}

std::vector<TTrackedBox> CDynamicKFSLAM2D::trackedBoxes() const
{
	const estimator::CBoxTracker* tracker = m_router ? m_router->boxTracker() : nullptr;
	if (!tracker) return {};
	const Eigen::Vector3d ego(m_xkk[0], m_xkk[1], m_xkk[2]);
	// The object of each box track read as a moving object in the step (its corners' hint).
	std::map<int32_t, int32_t> objectOf;
	for (const estimator::TRoutedReading& m : m_routed.readings)
		if (m.object >= 0 && m.reading.hint >= 0) objectOf[m.reading.hint] = m.object;
	std::vector<TTrackedBox> out;
	for (const estimator::TBoxTrack& t : tracker->tracks())
	{
		if (t.state != estimator::ETrackState::Confirmed || !t.updated) continue;
		Eigen::Vector3d world = t.x.head<3>();
		// A box mapped as four static landmarks: the map's centre (after this step's update).
		Eigen::Vector2d c;
		Eigen::Matrix2d C;
		if (boxPrediction(estimator::CBoxRouter::cornerIds(t.id), c, C)) world.head<2>() = c;
		// A moving object: the filter's pose of its founders' centroid (the box centre when
		// the four corners founded it), if it has one of this step.
		if (const auto o = objectOf.find(t.id); o != objectOf.end())
			if (const auto p = getObjectWorldPose(o->second); p && p->step == m_step)
				world.head<2>() = p->mean.head<2>();
		TTrackedBox b;
		b.track = t.id;
		b.cls = t.cls;
		b.score = t.score;
		b.pose = models::poseDifference(world, ego);
		b.extent = t.x.segment<2>(3);
		out.push_back(b);
	}
	return out;
}
}  // namespace dynslam
