/** The default definitions of dynslam/apps/slam_services.h: CStaticBaselineBackend, linked in.
 * Keep this file to these two functions (a program that defines them itself must not need
 * anything else from here). */
#include <dynslam/apps/CStaticBaselineBackend.h>
#include <dynslam/apps/slam_services.h>

namespace dynslam::apps
{
std::unique_ptr<ISlamBackend> slamStaticBaseline(const std::string& kind,
                                                 const mrpt::config::CConfigFileBase& ini,
                                                 std::ostream* optionsDump)
{
	auto f = std::make_unique<CStaticBaselineBackend>(
	    kind == "static_all" ? CStaticBaselineBackend::Mode::AllFeatures
	                         : CStaticBaselineBackend::Mode::StaticOnly);
	f->loadOptions(ini, "RangeBearingKFSLAM");
	if (optionsDump)
	{
		*optionsDump << "# [RangeBearingKFSLAM] and [RangeBearingKFSLAM_KalmanFilter] "
		                "(mrpt::slam::CRangeBearingKFSLAM2D, "
		             << f->name() << ")";
		f->dumpOptions(*optionsDump);
	}
	return f;
}

bool slamStaticBaselineJointCov(const ISlamBackend& backend, Eigen::MatrixXd& C)
{
	const auto* st = dynamic_cast<const CStaticBaselineBackend*>(&backend);
	if (!st) return false;
	C = st->landmarksJointCov();
	return true;
}
}  // namespace dynslam::apps
