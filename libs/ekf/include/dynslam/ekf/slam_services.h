#pragma once
/** @file slam_services.h
 * The filter's only uses of MRPT's slam library (libmrpt-slam), behind two factories:
 * outlier_method = jcbb (CJcbbUpdateEngine) and the association of ID -1 readings under
 * feature_labels = classify (mrpt_static_association.h). CDynamicKFSLAM2D::reset() calls these
 * instead of the classes, so that a program can start without libmrpt-slam.
 *
 * Their definitions in libdynslam_ekf (slam_services.cpp, nothing else in that object file) are
 * the default. A program may define both functions itself: the linker then takes its own and
 * never pulls slam_services.cpp.o (nor CJcbbUpdateEngine.cpp.o, mrpt_static_association.cpp.o)
 * out of the archive. dynslam-montecarlo does so (apps/dynslam-montecarlo/slam_services_lazy.cpp):
 * half of its start-up was the dynamic linking of libmrpt-slam's dependency chain (vision,
 * OpenCV, FFmpeg, Qt; doc/results/performance.md section 14), which it now loads on first use. */
#include <dynslam/estimator/unknown_id_association.h>
#include <dynslam/estimator/update_engine.h>

#include <memory>

namespace dynslam
{
/** makeMrptStaticAssociation(p) (mrpt_static_association.h). */
estimator::StaticAssociationFn slamStaticAssociation(const estimator::TUnknownIdParams& p);
/** std::make_unique<CJcbbUpdateEngine>(confidence) (CJcbbUpdateEngine.h). */
std::unique_ptr<estimator::IUpdateEngine> slamJcbbEngine(double confidence);
}  // namespace dynslam
