/** CCompareApp: the class scores of rows that classify (feature_labels = classify). */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/class_ground_truth.h>
#include <dynslam/eval/class_metrics.h>

#include <filesystem>

namespace dynslam::apps
{
std::optional<eval::TMetricsRow::TClassScores> CCompareApp::classScores(
    const TClassDecisions& d) const
{
	const std::string file = groundTruthUsed + "_gt_classes.csv";
	if (!std::filesystem::exists(file))
	{
		MRPT_LOG_WARN_FMT("no class ground truth %s: the class_* columns stay empty", file.c_str());
		return std::nullopt;
	}
	const std::vector<TReadingClass> truth = readClassGroundTruth(file);
	if (truth.size() != d.decisions.size())
	{
		MRPT_LOG_WARN_FMT("%s has %zu readings, the run %zu: the class_* columns stay empty",
		                  file.c_str(), truth.size(), d.decisions.size());
		return std::nullopt;
	}
	const eval::TBinaryScores s = eval::perReadingScores(truth, d.decisions);
	return eval::TMetricsRow::TClassScores{s.precision, s.recall, s.f1,
	                                       eval::groupingAri(truth, d.groups)};
}

void TClassDecisions::add(const estimator::TRoutedStep& step)
{
	using estimator::Route;
	for (const auto& m : step.readings)
	{
		const bool st = m.route == Route::StaticKnown || m.route == Route::StaticNew;
		steps.push_back(stepsAdded);
		ids.push_back(m.reading.id);
		decisions.push_back(m.candidate     ? eval::Decision::Undecided
		                    : st            ? eval::Decision::Static
		                    : m.object >= 0 ? eval::Decision::Moving
		                                    : eval::Decision::Undecided);
		groups.push_back(m.candidate || st ? -1 : m.identity >= 0 ? m.identity : m.object);
	}
	restarted += step.restarted;
	split += step.split;
	joined += step.joined;
	held += step.held;
	skipped_unknown_id += step.skipped_unknown_id;
	linked += step.linked;
	link_ambiguous += step.link_ambiguous;
	hint_track_conflicts += step.hint_track_conflicts;
	hint_group_conflicts += step.hint_group_conflicts;
	++stepsAdded;
}

std::string TClassDecisions::countsLine(const std::string& filter) const
{
	return filter + ": tracks restarted after a break (ID reused) " + std::to_string(restarted) +
	       ", split off their object " + std::to_string(split) + ", joined an earlier object " +
	       std::to_string(joined) + "; readings held back " + std::to_string(held) +
	       ", ID -1 skipped " + std::to_string(skipped_unknown_id) +
	       "; objects linked after a break " + std::to_string(linked) + " (" +
	       std::to_string(link_ambiguous) +
	       " with two or more candidates: the nearest); contradicting hints: readings " +
	       std::to_string(hint_track_conflicts) + ", object-steps " +
	       std::to_string(hint_group_conflicts) + "\n";
}
}  // namespace dynslam::apps
