/** dynslam-compare's classification figures (CCompareApp.h, writeClassFigures). */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/app_common.h>
#include <dynslam/eval/class_figures.h>
#include <dynslam/eval/figures.h>

#include <filesystem>

namespace dynslam::apps
{
std::vector<std::string> writeClassFigures(const std::string& outDir, const std::string& filter,
                                           const io::TGroundTruth* gt,
                                           const eval::TRunEstimates& est, const TClassDecisions& d,
                                           const std::vector<io::TReadingClass>* classTruth)
{
	static const std::vector<io::TReadingClass> kNone;
	// another run's truth (other reading count): decisions only
	const std::vector<io::TReadingClass>& truth =
	    classTruth && classTruth->size() == d.decisions.size() ? *classTruth : kNone;
	std::vector<std::string> written;
	const auto save = [&](const std::string& name, const mrpt::img::CImage& img)
	{
		const std::string p = (std::filesystem::path(outDir) / (filter + name)).string();
		eval::savePng(img, p);
		written.push_back(p);
	};
	save("_class_map.png",
	     eval::drawClassMap(gt, est, truth, filter + ": the map coloured by the decided class"));
	save("_class_timeline.png",
	     eval::drawDecisionTimeline({d.steps, d.ids, d.decisions}, truth,
	                                filter + ": decision per track and step"));
	return written;
}
}  // namespace dynslam::apps
