#pragma once
/** @file figure.h
 * A schematic of a scenario like the paper's Fig. 1, drawn headless with mrpt::img::CImage:
 * ego path red, objects green / blue / purple (then further colours), static landmarks
 * yellow, each object's features at its first sighting as small squares, the road (highway)
 * in grey. Long scenes get a stretched lateral axis (the factor is printed in the image). */
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/TScenarioOptions.h>

#include <string>

namespace dynslam::sim
{
/** Draws the ground truth and saves it as PNG (throws std::runtime_error if saving fails). */
void drawScenarioFigure(const io::TGroundTruth& gt, const TScenarioOptions& o,
                        const std::string& pngPath, int width = 1800, int height = 620);
}  // namespace dynslam::sim
