/** CDynamicKFSLAM2D: the result getters, one-line calls of the state reader (src/results/reader.h:
 * the whole state through the const view ekf::TFilterView, with the output term of the prior
 * gauge, src/gauge/prior_gauge.h), and the slot view the layout's changes rebuild. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include "gauge/prior_gauge.h"
#include "modules/module_list.h"
#include "modules/object_motion.h"
#include "modules/odometry_bias.h"
#include "results/reader.h"

namespace dynslam
{
namespace results = ekf::results;
namespace
{
ekf::TFilterView viewOf(const CDynamicKFSLAM2D& f) { return {f}; }
}  // namespace

mrpt::poses::CPosePDFGaussian CDynamicKFSLAM2D::getEgoPose() const
{
	return results::egoPose(viewOf(*this));
}

std::vector<TStaticLandmarkEstimate> CDynamicKFSLAM2D::getStaticLandmarks() const
{
	return results::staticLandmarks(viewOf(*this));
}

std::vector<TStaticLandmarkEstimate> CDynamicKFSLAM2D::getDroppedStaticLandmarks() const
{
	return results::droppedStaticLandmarks(viewOf(*this));
}

std::vector<TObjectFeatureEstimate> CDynamicKFSLAM2D::getObjectFeatures() const
{
	return results::objectFeatures(viewOf(*this));
}

std::map<int32_t, TObjectTrack> CDynamicKFSLAM2D::getObjectTracks() const
{
	std::map<int32_t, TObjectTrack> out = results::objectTracks(viewOf(*this));
	if (const ekf::CObjectMotionModule* motion = m_modules->objectMotion())
		motion->attachModeProbabilities(out);  // object_model = mm
	return out;
}

size_t CDynamicKFSLAM2D::liveObjectCount() const { return results::liveObjectCount(viewOf(*this)); }

std::optional<TObjectWorldPose> CDynamicKFSLAM2D::getObjectWorldPose(int32_t object) const
{
	return results::objectWorldPose(viewOf(*this), object);
}

std::map<int32_t, TObjectWorldPose> CDynamicKFSLAM2D::getObjectWorldPoses() const
{
	return results::objectWorldPoses(viewOf(*this));
}

void CDynamicKFSLAM2D::getStateWithoutPads(Eigen::VectorXd& x, Eigen::MatrixXd& P,
                                           std::vector<std::string>* labels) const
{
	results::stateWithoutPads(viewOf(*this), x, P, labels);
}

std::vector<size_t> CDynamicKFSLAM2D::padIndices() const
{
	return results::padIndices(viewOf(*this));
}

Eigen::MatrixXd CDynamicKFSLAM2D::gaugeJacobian() const
{
	return results::gaugeJacobian(viewOf(*this));
}

Eigen::MatrixXd CDynamicKFSLAM2D::reportedCov() const
{
	return results::reportedCov(viewOf(*this));
}

std::optional<std::pair<Eigen::VectorXd, Eigen::MatrixXd>> CDynamicKFSLAM2D::getOdometryBias() const
{
	return ekf::COdometryBiasModule::estimate(viewOf(*this).working());
}

void CDynamicKFSLAM2D::onLayoutChanged()
{
	static thread_local std::vector<std::pair<int32_t, size_t>> statics;
	results::slotsOf(m_layout, m_slots, &statics);
	results::assignInPlace(m_staticBlock, statics);
}

void CDynamicKFSLAM2D::slotsOf(const estimator::CPaddedLayout& layout, std::vector<TSlot>& slots,
                               std::vector<std::pair<int32_t, size_t>>* statics)
{
	results::slotsOf(layout, slots, statics);
}
}  // namespace dynslam
