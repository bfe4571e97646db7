/** object_model = mm on the tunnel (600 m without static landmarks, two cars beside the ego):
 * config/tunnel.ini (the cars drive steadily: the truth follows cv) and
 * config/tunnel_manoeuvres.ini (both cars change lanes, one brakes, inside the gap: the truth
 * leaves cv). Filtered with config/compare_tunnel.ini (setting E, the anchored gauge) and
 * object_model = paper, cv or mm with mm's defaults; seeds 2810..2814. Measured: the ego ATE of
 * the whole run, the ego NEES in the gap, and the mode probabilities. */
#include <dynslam/common/config_include.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <map>

using namespace dynslam;

namespace
{
struct TTunnelRun
{
	double ate = 0;                    ///< ego position RMSE over the run [m]
	double gapNees = 0;                ///< mean ego NEES (3 dof) over the gap's steps
	double probError = 0;              ///< worst |sum of an object's mode probabilities - 1|
	size_t gatedOut = 0, updates = 0;  ///< object readings gated out / used in updates
	/** Per object: the largest manoeuvre probability in [t0, t1] and the mean of cv + turn
	 * outside it (steady driving). */
	std::map<int32_t, double> manoeuvrePeak, steadyCvTurn;
};

TTunnelRun runTunnel(const char* scenarioIni, const std::string& model, uint32_t seed,
                     double t0 = 1e9, double t1 = -1)
{
	sim::TScenarioOptions o = sim::loadScenario(scenarioIni);
	o.noise_seed = seed;
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun run = sim::simulateMeasurements(gt, o, seed);
	CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	mrpt::config::CConfigFileMemory ini;
	config::loadIniWithIncludes(DYNSLAM_CONFIG_DIR "/compare_tunnel.ini", ini);
	f.loadOptions(ini);
	f.options.object_model = model;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0 = o.Sigma_0;
	f.reset();
	TTunnelRun r;
	int ne = 0;
	std::map<int32_t, int> steadySamples;
	for (size_t k = 0; k < run.actions.size(); ++k)
	{
		f.processActionObservation(run.actions[k], run.frames[k]);
		r.gatedOut += f.getLastStepReport().object_gated_out;
		r.updates += f.getLastStepReport().object_feature_updates;
		const auto pdf = f.getEgoPose();
		const Eigen::Vector3d d(pdf.mean.x() - gt.ego[k][0], pdf.mean.y() - gt.ego[k][1],
		                        models::wrapToPi(pdf.mean.phi() - gt.ego[k][2]));
		r.ate += d.head<2>().squaredNorm();
		if (gt.ego[k][0] >= 200 && gt.ego[k][0] <= 800)
		{
			r.gapNees += d.dot(pdf.cov.asEigen().ldlt().solve(d));
			++ne;
		}
		const double t = double(k) * o.dt;
		for (const auto& [obj, mu] : f.getObjectModeProbabilities())
		{
			r.probError = std::max(r.probError, std::abs(mu.sum() - 1.0));
			if (t >= t0 && t <= t1)
				r.manoeuvrePeak[obj] = std::max(r.manoeuvrePeak[obj], mu[3]);
			else if (t > 2.0)  // after the first second of the velocity
			{
				r.steadyCvTurn[obj] += mu[1] + mu[2];
				++steadySamples[obj];
			}
		}
	}
	r.ate = std::sqrt(r.ate / double(run.actions.size()));
	r.gapNees /= ne;
	for (auto& [obj, s] : r.steadyCvTurn) s /= steadySamples[obj];
	return r;
}

struct TMeans
{
	double paper = 0, cv = 0, mm = 0;
	double worstCv = 0, worstMm = 0;  ///< the largest per-seed ATE ratio to paper
	double neesCv = 0, neesMm = 0;    ///< mean ego NEES (3 dof) in the gap over the seeds
	size_t gatedCv = 0, gatedMm = 0, usedCv = 0, usedMm = 0;  ///< object readings, all seeds
};

/** Mean ATE of paper, cv and mm over the seeds. */
TMeans meanAte(const char* scenarioIni, const char* name)
{
	TMeans m;
	const int seeds = 5;
	for (uint32_t s = 2810; s < 2810 + seeds; ++s)
	{
		const double p = runTunnel(scenarioIni, "paper", s).ate;
		const TTunnelRun rc = runTunnel(scenarioIni, "cv", s), rm = runTunnel(scenarioIni, "mm", s);
		const double c = rc.ate, x = rm.ate;
		m.gatedCv += rc.gatedOut;
		m.gatedMm += rm.gatedOut;
		m.usedCv += rc.updates;
		m.usedMm += rm.updates;
		m.neesCv += rc.gapNees / seeds;
		m.neesMm += rm.gapNees / seeds;
		std::printf("[ measured ] %s seed %u: ATE paper %.4f, cv %.4f, mm %.4f m\n", name, s, p, c,
		            x);
		m.worstCv = std::max(m.worstCv, c / p);
		m.worstMm = std::max(m.worstMm, x / p);
		m.paper += p / seeds;
		m.cv += c / seeds;
		m.mm += x / seeds;
	}
	std::printf(
	    "[ measured ] %s mean ATE: paper %.4f, cv %.4f (%.2f x paper), mm %.4f (%.2f x); "
	    "worst seed: cv %.2f x, mm %.2f x paper; ego NEES in the gap: cv %.2f, mm %.2f\n",
	    name, m.paper, m.cv, m.cv / m.paper, m.mm, m.mm / m.paper, m.worstCv, m.worstMm, m.neesCv,
	    m.neesMm);
	std::printf("[ measured ] %s object readings gated out / used: cv %zu / %zu, mm %zu / %zu\n",
	            name, m.gatedCv, m.usedCv, m.gatedMm, m.usedMm);
	return m;
}
}  // namespace

// mm's defaults were chosen on seeds 2820..2829 of both scenarios (doc/results/multiple_model.md);
// these seeds (2810..2814) were not used for that.
// Measured 2026-11-29: paper 0.616, cv 0.433 (0.70 x), mm 0.450 m (0.73 x); worst seed cv
// 5.62 x, mm 2.28 x paper; ego NEES in the gap cv 16.8, mm 2.12 (3 dof). mm does not yet "never
// hurt" (issue 28): it halves cv's worst case and stays consistent where cv is overconfident.
TEST(MultipleModelTunnel, ManoeuvresInTheGapHelpOnAverageAndHalveCvsWorstCase)
{
	const TMeans m = meanAte(DYNSLAM_CONFIG_DIR "/tunnel_manoeuvres.ini", "manoeuvres");
	EXPECT_LT(m.mm, m.paper);  // the objects help on average, also when they manoeuvre
	EXPECT_LT(m.worstMm, 0.5 * m.worstCv);
	EXPECT_LT(m.neesMm, 3.0);  // 3 dof: mm is not overconfident where it manoeuvres
	// The gate does not lock mm's objects out: the manoeuvre mode widens the prediction.
	// Measured: readings gated out cv 2830, mm 2 (of 4760).
	EXPECT_LT(m.gatedMm * 4, m.gatedCv);
}

// Measured 2026-11-29: paper 0.616, cv 0.052 (0.09 x), mm 0.048 m (0.08 x); worst seed cv
// 0.16 x, mm 0.17 x paper.
TEST(MultipleModelTunnel, SteadyTunnelKeepsTheObjectsGain)
{
	const TMeans m = meanAte(DYNSLAM_CONFIG_DIR "/tunnel.ini", "steady");
	EXPECT_LT(m.mm, 0.25 * m.paper);
	EXPECT_LT(m.mm, 1.5 * m.cv);
	EXPECT_LT(m.worstMm, 0.6);
}

TEST(MultipleModelTunnel, ModeProbabilitiesFollowTheManoeuvres)
{
	// Agent2 (object 1) brakes at 24-26 s, changes lanes at 28-31 s, speeds up at 30-33 s;
	// Agent1 (object 0) changes lanes at 20-23 s and 32-35 s.
	const TTunnelRun man =
	    runTunnel(DYNSLAM_CONFIG_DIR "/tunnel_manoeuvres.ini", "mm", 2810, 20.0, 35.0);
	const TTunnelRun steady = runTunnel(DYNSLAM_CONFIG_DIR "/tunnel.ini", "mm", 2810, 20.0, 35.0);
	for (const int32_t obj : {0, 1})
		std::printf(
		    "[ measured ] object %d: manoeuvre peak %.3f (steady run %.3f); cv + turn "
		    "outside 20-35 s %.3f (steady run %.3f)\n",
		    obj, man.manoeuvrePeak.at(obj), steady.manoeuvrePeak.at(obj), man.steadyCvTurn.at(obj),
		    steady.steadyCvTurn.at(obj));
	EXPECT_LT(man.probError, 1e-12);
	for (const int32_t obj : {0, 1})
	{
		EXPECT_GT(man.manoeuvrePeak.at(obj), 0.5) << obj;
		EXPECT_LT(steady.manoeuvrePeak.at(obj), 0.5) << obj;
		EXPECT_GT(steady.steadyCvTurn.at(obj), 0.8) << obj;
	}
}
