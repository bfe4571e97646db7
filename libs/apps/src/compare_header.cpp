/** dynslam-compare's header lines on the console (config, rawlog, ground truth, noise). */
#include <dynslam/apps/CCompareApp.h>

#include <iostream>

namespace dynslam::apps
{
void CCompareApp::printHeader(size_t steps) const
{
	if (quiet) return;
	std::cout << "dynslam-compare: config " << iniFile << "\n  rawlog " << data.rawlog << " ("
	          << steps << " steps)\n  ground truth "
	          << (hasGroundTruth ? groundTruthUsed : std::string("none")) << "\n";
	if (!noiseUsed.empty()) std::cout << "  " << noiseUsed << "\n";
}
}  // namespace dynslam::apps
