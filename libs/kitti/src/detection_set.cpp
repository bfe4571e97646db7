#include <dynslam/kitti/detection_files.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>

namespace dynslam::kitti
{
namespace
{
void checkOptions(const TDetectionOptions& o)
{
	if (o.classes.empty()) throw std::invalid_argument("detection options: no class");
	std::set<std::string> seen;
	for (const auto& c : o.classes)
	{
		if (c != "Pedestrian" && c != "Car" && c != "Cyclist")
			throw std::invalid_argument("detection options: class '" + c +
			                            "': expected Pedestrian, Car or Cyclist");
		if (!seen.insert(c).second)
			throw std::invalid_argument("detection options: class '" + c + "' given twice");
	}
	if (std::isnan(o.min_score) || o.min_score == std::numeric_limits<double>::infinity())
		throw std::invalid_argument("detection options: min_score must be a number or -inf");
}

TDetectionSummary::TClass countClass(const TKittiDetectionFile& d, double minScore,
                                     size_t numFrames)
{
	TDetectionSummary::TClass c;
	c.per_frame.assign(numFrames, 0);
	c.lines = d.detections.size();
	for (const auto& x : d.detections)
	{
		if (x.score >= minScore)
		{
			++c.kept;
			++c.per_frame[size_t(x.frame)];
		}
		else
			++c.below_threshold;
	}
	for (size_t k = 0; k < numFrames; ++k)
	{
		c.frames_with_detections += c.per_frame[k] > 0;
		if (c.per_frame[k] > c.max_per_frame)
		{
			c.max_per_frame = c.per_frame[k];
			c.max_frame = int(k);
		}
	}
	return c;
}
}  // namespace

TDetectionSummary readDetectionSet(const std::string& detectionsDir, const std::string& calibDir,
                                   const std::string& sequence, const TDetectionOptions& opts,
                                   size_t numFrames, const std::string& posesPath,
                                   std::vector<std::vector<TKittiDetection>>* kept)
{
	checkOptions(opts);
	checkSequenceName(sequence);
	for (const auto& d : {detectionsDir, calibDir})
		if (!std::filesystem::is_directory(d)) throw std::runtime_error(d + ": folder not found");
	// read and checked; not used (the detections are in the labels' camera frame already)
	readCalib(sequenceFile(calibDir, sequence));
	TDetectionSummary s;
	s.min_score = opts.min_score;
	std::vector<TKittiDetectionFile> files;
	for (const auto& cls : opts.classes)  // read everything before counting anything
	{
		const std::string dir = (std::filesystem::path(detectionsDir) / cls).string();
		if (!std::filesystem::is_directory(dir))
			throw std::runtime_error(dir + ": folder not found (class " + cls +
			                         " of detection_classes)");
		files.push_back(readDetections(sequenceFile(dir, sequence), cls));
		checkDetectionsAgainstFrames(files.back(), numFrames, posesPath);
	}
	for (const auto& f : files) s.classes[f.type] = countClass(f, opts.min_score, numFrames);
	if (kept)
	{
		kept->assign(numFrames, {});
		for (const auto& f : files)
			for (const auto& d : f.detections)
				if (d.score >= opts.min_score) (*kept)[size_t(d.frame)].push_back(d);
	}
	return s;
}

std::string TDetectionSummary::toText() const
{
	std::ostringstream o;
	o << "  detections (score >= " << min_score << "): written to the rawlog " << written
	  << " boxes in " << frames_written << " frames (" << beyond_range
	  << " beyond max_range not written)\n";
	for (const auto& [cls, c] : classes)
	{
		o << "    " << cls << ": " << c.lines << " lines, kept " << c.kept << ", below threshold "
		  << c.below_threshold << "; frames with detections " << c.frames_with_detections << " of "
		  << c.per_frame.size() << ", at most " << c.max_per_frame << " per frame";
		if (c.max_frame >= 0) o << " (frame " << c.max_frame << ")";
		o << ", mean " << (c.per_frame.empty() ? 0.0 : double(c.kept) / double(c.per_frame.size()))
		  << " per frame\n";
	}
	return o.str();
}
}  // namespace dynslam::kitti
