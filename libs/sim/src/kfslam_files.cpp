/** @file kfslam_files.cpp
 * Ground-truth files in the formats MRPT's kf-slam reads (KFSLAMApp, MRPT 2.5.8):
 * ground_truth_file (landmarks, ID in column 6), ground_truth_file_robot (6 columns) and
 * ground_truth_data_association (timestamp, index in observation, true label). */
#include <dynslam/sim/scenario.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace dynslam::sim
{
namespace
{
struct FileCloser
{
	void operator()(std::FILE* f) const
	{
		if (f) std::fclose(f);
	}
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

FilePtr openText(const std::string& path)
{
	FilePtr f(std::fopen(path.c_str(), "wb"));
	if (!f) throw std::runtime_error("writeKfSlamGroundTruth: cannot write " + path);
	return f;
}

std::string join(const std::string& dir, const std::string& name)
{
	return (std::filesystem::path(dir) / name).string();
}
}  // namespace

void writeKfSlamGroundTruth(const io::TGroundTruth& gt, const TSimulatedRun& run,
                            const std::string& dir, const std::string& base)
{
	std::filesystem::create_directories(dir);
	{
		auto f = openText(join(dir, base + "_gt_landmarks.txt"));
		std::fprintf(f.get(), "%% Static landmarks (CLandmarksMap::saveToTextFile columns):\n");
		std::fprintf(f.get(), "%% x y z type seenCount tLastSeen ID\n");
		for (const auto& [id, p] : gt.landmarks)
			std::fprintf(f.get(), "%.9f %.9f 0 0 0 0 %d\n", p[0], p[1], int(id));
	}
	{
		auto f = openText(join(dir, base + "_gt_robot_path.txt"));
		std::fprintf(f.get(), "%% Ego ground truth, one row per step k (pose of SF_k):\n");
		std::fprintf(f.get(), "%% x y z yaw pitch roll\n");
		for (const auto& x : gt.ego)
			std::fprintf(f.get(), "%.9f %.9f 0 %.12f 0 0\n", x[0], x[1], x[2]);
	}
	{
		auto f = openText(join(dir, base + "_gt_data_association.txt"));
		std::fprintf(
		    f.get(),
		    "%% Data-association ground truth for kf-slam (ground_truth_data_association):\n");
		std::fprintf(
		    f.get(),
		    "%% timestamp (Clock::toDouble of the observation) index_in_observation landmark_ID\n");
		for (const auto& sf : run.frames)
		{
			const auto obs = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>();
			if (!obs) continue;
			const double t = mrpt::Clock::toDouble(obs->timestamp);
			for (size_t i = 0; i < obs->sensedData.size(); ++i)
				std::fprintf(f.get(), "%.17g %d %d\n", t, int(i),
				             int(obs->sensedData[i].landmarkID));
		}
	}
}
}  // namespace dynslam::sim
