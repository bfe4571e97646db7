/** CCompareApp: the class scores of rows that classify (feature_labels = classify). */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/data_files.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/eval/object_matching.h>
#include <dynslam/io/class_ground_truth.h>

#include <filesystem>
#include <set>

namespace dynslam::apps
{
namespace
{
/** "agent cells: agent 1 <- object 0 (time 0 step 1, 4 features; 2 candidates), agent 3: no
 * estimated object (empty)" (doc/metrics.md "Objects of classifying rows"). */
std::string agentNote(const std::vector<eval::TAgentMatch>& agents)
{
	std::string s =
	    "agent_* RMSE cells, each true object against its estimated object with the "
	    "most of its readings, from that object's time 0:";
	for (size_t k = 0; k < agents.size(); ++k)
	{
		const auto& a = agents[k];
		s += (k ? ", agent " : " agent ") + std::to_string(k + 1);
		if (a.estimated < 0)
		{
			s += ": no estimated object (cells empty)";
			continue;
		}
		s += " <- object " + std::to_string(a.estimated) + " (time 0 step " +
		     std::to_string(a.first_step) + ", " + std::to_string(a.features_matched) +
		     " features matched" +
		     (a.candidates > 1 ? "; " + std::to_string(a.candidates) + " candidates" : "") + ")";
	}
	return s;
}
}  // namespace

void CCompareApp::scoreObjects(eval::TMetricsRow& row, const TClassDecisions* classifying,
                               const eval::TRunEstimates& est)
{
	if (!classifying)
	{
		row.velocity = eval::objectVelocityErrors(gt, est);  // numbered as the truth
		return;
	}
	const TClassDecisions& d = *classifying;
	const bool mrptFiles = isMrptGroundTruthSpec(groundTruthUsed);
	const std::string file = groundTruthUsed + "_gt_classes.csv";
	std::string why;
	const std::vector<io::TReadingClass>* classes = classTruth();
	if (!classes && mrptFiles)
		why = "MRPT's ground truth (" + groundTruthUsed +
		      ") has no classes of readings (dynslam-simulate's BASE_gt_classes.csv has)";
	else if (!classes)
		why = "no class ground truth " + file;
	else if (classes->size() != d.decisions.size())
		why = file + " has " + std::to_string(classes->size()) + " readings, the run " +
		      std::to_string(d.decisions.size());
	if (!why.empty())
	{
		// The agent_* cells by number would compare unrelated objects: emptied.
		eval::blankObjectColumns(row.metrics);
		MRPT_LOG_WARN_FMT("%s: the class_* and object columns stay empty", why.c_str());
		objectNotes.push_back(row.filter + ": " + why +
		                      ": class_* and object columns (agent_* RMSE, obj_*) left empty, "
		                      "its object numbers are the router's, not the truth's");
		return;
	}
	const std::vector<io::TReadingClass>& truth = *classes;
	const eval::TBinaryScores s = eval::perReadingScores(truth, d.decisions);
	row.classes = eval::TMetricsRow::TClassScores{s.precision, s.recall, s.f1,
	                                              eval::groupingAri(truth, d.groups)};
	const auto match = eval::matchObjectsByReadings(d.objects, truth);
	size_t unmatched = 0;
	std::set<int32_t> trueHit;
	for (const auto& [e, t] : match)
	{
		if (t < 0) ++unmatched;
		if (t >= 0) trueHit.insert(t);
	}
	row.velocity = eval::classifyingVelocityErrors(gt, est, d.objects, &truth);
	const auto agents =
	    eval::scoreClassifyingAgents(row.metrics, gt, est, {d.objects, d.features}, truth);
	objectNotes.push_back(
	    row.filter + ": " + std::to_string(match.size()) + " estimated objects matched to " +
	    std::to_string(trueHit.size()) + " true objects by the majority of their readings (" +
	    std::to_string(unmatched) + " without a true object); " + agentNote(agents));
	// Objects joined across track breaks (classify_link): one identity per true object is the
	// ideal; impure identities are wrong links (doc/metrics.md "Objects of classifying rows").
	const eval::TIdentityCounts ids = eval::identityCounts(truth, d.groups);
	identities[row.filter] = ids;
	objectNotes.push_back(row.filter + ": " + std::to_string(ids.identities) +
	                      " object identities (objects joined across track breaks) for " +
	                      std::to_string(ids.true_objects) + " true moving objects; " +
	                      std::to_string(ids.impure) +
	                      " identities hold two or more true objects, " +
	                      std::to_string(ids.split) + " true objects are split over two or more");
}

void CCompareApp::clearResults()
{
	runs.clear();
	rows.clear();
	objectNotes.clear();
	identities.clear();
	failedFilters.clear();
	writtenFiles.clear();
	m_classTruth.reset();
	m_classTruthRead = false;
	classTruthFilesRead = 0;
}

const std::vector<io::TReadingClass>* CCompareApp::classTruth()
{
	if (!m_classTruthRead)
	{
		m_classTruthRead = true;
		const std::string file = groundTruthUsed + "_gt_classes.csv";
		if (!isMrptGroundTruthSpec(groundTruthUsed) && std::filesystem::exists(file))
		{
			m_classTruth = io::readClassGroundTruth(file);
			++classTruthFilesRead;
		}
	}
	return m_classTruth ? &*m_classTruth : nullptr;
}

void TClassDecisions::add(const estimator::TRoutedStep& step)
{
	using estimator::Route;
	for (const auto& m : step.readings)
	{
		const bool st = m.route == Route::StaticKnown || m.route == Route::StaticNew;
		steps.push_back(stepsAdded);
		ids.push_back(m.reading.id);
		objects.push_back(m.candidate || st ? -1 : m.object);
		features.push_back(m.candidate || st || m.object < 0 ? -1 : m.feature);
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
