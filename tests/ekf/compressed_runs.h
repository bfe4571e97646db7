#pragma once
/** Runs shared by the compressed-EKF tests (test_compressed.cpp, test_compressed_engines.cpp):
 * the highway rawlog, a generated scenario and a ring with revisits, and the comparison of a
 * compressed filter's whole estimate with a full one's, matched by entry label. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include <map>

#include "synthetic_world.h"

namespace compressed_runs
{
using namespace dynslam;

struct TSteps
{
	std::vector<mrpt::obs::CActionCollection::Ptr> acts;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> sfs;
	Eigen::Matrix2d Sigma_v;
	Eigen::Matrix3d Sigma_0;
};

inline TSteps highway()
{
	mrpt::obs::CRawlog log;
	if (!log.loadFromRawLogFile(DYNSLAM_DATASETS_DIR "/highway.rawlog"))
		throw std::runtime_error("highway.rawlog");
	TSteps s;
	for (size_t i = 0; i + 1 < log.size(); ++i)
		if (log.getType(i) == mrpt::obs::CRawlog::etActionCollection &&
		    log.getType(i + 1) == mrpt::obs::CRawlog::etSensoryFrame)
		{
			s.acts.push_back(log.getAsAction(i));
			s.sfs.push_back(log.getAsObservations(i + 1));
			++i;
		}
	const auto o = sim::loadScenario(DYNSLAM_DATASETS_DIR "/highway_scenario.ini");
	s.Sigma_v = o.Sigma_v;
	s.Sigma_0 = o.Sigma_0;
	return s;
}

inline TSteps generated()
{
	const auto o = sim::loadScenario(DYNSLAM_CONFIG_DIR "/generated_small_scenario.ini");
	const auto run = sim::simulateMeasurements(sim::buildGroundTruth(o), o, 7);
	return {run.actions, run.frames, o.Sigma_v, o.Sigma_0};
}

/** A ring of 60 landmarks driven 2.5 times round (every landmark read again after a lap), 2
 * objects in convoy. */
inline TSteps ring()
{
	dynslam_bench::TSyntheticOptions o;
	o.landmarks = 60;
	o.spacing = 6;
	o.objects = 2;
	o.max_visible = 12;
	o.seed = 3;
	dynslam_bench::CSyntheticWorld w(o);
	TSteps s;
	s.Sigma_v = o.Sigma_v;
	s.Sigma_0 = o.Sigma_w;
	for (int k = 0; k < 480; ++k)
	{
		s.acts.emplace_back();
		s.sfs.emplace_back();
		w.next(s.acts.back(), s.sfs.back());
	}
	return s;
}

inline double relErr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
	return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, a.cwiseAbs().maxCoeff());
}

/** The whole estimate of `c` (compressed; this is a global update) against `f` (full), matched
 * by entry label; dropped landmarks and object tracks (recorded poses) by ID. Returns the
 * largest relative error of the means and of the covariance. */
inline std::pair<double, double> compare(const CDynamicKFSLAM2D& f, const CDynamicKFSLAM2D& c,
                                         const std::string& where)
{
	Eigen::VectorXd x1, x2;
	Eigen::MatrixXd P1, P2;
	std::vector<std::string> l1, l2;
	f.getStateWithoutPads(x1, P1, &l1);
	c.getStateWithoutPads(x2, P2, &l2);
	// The getters read an expanded copy: they leave the working state as it is.
	const size_t working = c.workingDim();
	if (l1.size() != l2.size())
	{
		ADD_FAILURE() << where << ": " << l1.size() << " vs " << l2.size() << " entries";
		return {1, 1};
	}
	std::map<std::string, int> at;
	for (size_t i = 0; i < l2.size(); ++i) at[l2[i]] = int(i);
	std::vector<int> perm;
	for (const auto& l : l1)
	{
		if (!at.count(l))
		{
			ADD_FAILURE() << where << ": " << l << " missing";
			return {1, 1};
		}
		perm.push_back(at[l]);
	}
	const double ex = relErr(x1, x2(perm)), eP = relErr(P1, P2(perm, perm));
	EXPECT_EQ(c.workingDim(), working) << where << ": a getter changed the working state";
	EXPECT_LE(ex, 1e-9) << where;
	EXPECT_LE(eP, 1e-9) << where;
	// Dropped landmarks, per ID in the order they were dropped (a landmark read again after its
	// drop is a new entry and may be dropped again).
	std::map<int32_t, std::vector<TStaticLandmarkEstimate>> d1, d2;
	for (const auto& e : allStaticLandmarks(f))
		if (!e.in_state) d1[e.id].push_back(e);
	for (const auto& e : allStaticLandmarks(c))
		if (!e.in_state) d2[e.id].push_back(e);
	EXPECT_EQ(d1.size(), d2.size()) << where;
	for (const auto& [id, v] : d1)
	{
		if (!d2.count(id) || d2[id].size() != v.size())
		{
			ADD_FAILURE() << where << ": landmark " << id << " dropped differently";
			continue;
		}
		for (size_t i = 0; i < v.size(); ++i)
		{
			EXPECT_LE((v[i].mean - d2[id][i].mean).norm(), 1e-9 * v[i].mean.norm()) << where;
			EXPECT_LE(relErr(v[i].cov, d2[id][i].cov), 1e-9) << where;
		}
	}
	const auto t1 = f.getObjectTracks(), t2 = c.getObjectTracks();
	EXPECT_EQ(t1.size(), t2.size()) << where;
	for (const auto& [obj, tr] : t1)
	{
		if (!t2.count(obj) || tr.poses.size() != t2.at(obj).poses.size())
		{
			ADD_FAILURE() << where << ": object " << obj << " track differs";
			continue;
		}
		for (size_t i = 0; i < tr.poses.size(); ++i)
			EXPECT_LE((tr.poses[i].mean - t2.at(obj).poses[i].mean).cwiseAbs().maxCoeff(), 1e-9)
			    << where;
	}
	return {ex, eP};
}

}  // namespace compressed_runs
