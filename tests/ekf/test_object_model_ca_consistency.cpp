/** object_model = ca: a consistency test on truth generated from its own model. The tunnel
 * (datasets/tunnel_scenario.ini: 600 m without static landmarks, two cars beside the ego) with the
 * true start drawn from the prior (start_from_prior, doc/simulator.md "Model-matched truth") and
 * the cars' motion replaced, in this test, by a draw of the ca filter's model: from the step after
 * its first sighting f (when the filter gives it a velocity) each car's offset from its constant-
 * velocity path starts with the filter's velocity-block prior (constant_acceleration.h:
 * acceleration a ~ N(0, Sa), velocity offset e/2 a + N(0, Sv), e = one step) and then moves with
 * constant acceleration driven by white jerk (the filter's Q, caProcessNoise). Filtered with
 * config/compare_tunnel.ini and object_model = ca with the truth's parameters. Measured: the Monte
 * Carlo mean of the NEES of each car's whole state [xi; v; a] (9 dof) at every step it has one, and
 * of the ego NEES in the gap, must lie inside the 95 % chi-square bounds of the run count. */
#include <dynslam/common/config_include.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/constant_acceleration.h>
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

using namespace dynslam;

namespace
{
/** Two-sided chi-square quantiles of k dof at standard-normal z (Wilson-Hilferty). */
std::pair<double, double> chi2Bounds(double k, double z)
{
	const double a = 1 - 2 / (9 * k), b = z * std::sqrt(2 / (9 * k));
	return {k * std::pow(a - b, 3), k * std::pow(a + b, 3)};
}

/** The truth's (and the filter's) ca parameters. */
estimator::TCvParams caParams()
{
	estimator::TCvParams p;
	p.dt = 0.5;
	p.velocity_prior_std = Eigen::Vector3d(0.05, 0.05, 0.005);
	p.accel_prior_std = Eigen::Vector3d(0.01, 0.01, 0.001);
	p.jerk_psd = Eigen::Vector3d(1e-5, 1e-5, 1e-7);
	return p;
}

/** The ground truth and each object's true state [xi; v; a] per step (NaN where not defined). */
struct TCaTruth
{
	io::TGroundTruth gt;
	std::vector<std::vector<Eigen::Matrix<double, 9, 1>>> state;
};

/** The scenario's truth with each object's motion offset by a draw of the ca model (seeded). */
TCaTruth caTruth(const sim::TScenarioOptions& o, uint32_t seed)
{
	const estimator::TCvParams p = caParams();
	TCaTruth t;
	t.gt = sim::buildGroundTruth(o);
	const size_t n = t.gt.numSteps();
	const double e = p.dt;
	std::mt19937 g(seed * 2654435761u + 17u);
	std::normal_distribution<double> N(0, 1);
	const Eigen::MatrixXd L =
	    estimator::caProcessNoise(p.jerk_psd, p.dt).llt().matrixL();  // 9 x 9, axes interleaved
	const Eigen::MatrixXd F = [&]
	{
		Eigen::MatrixXd J;
		estimator::caPredict(Eigen::VectorXd::Zero(9), p.dt, &J);
		return J;
	}();
	t.state.assign(t.gt.objects.size(), std::vector<Eigen::Matrix<double, 9, 1>>(
	                                        n, Eigen::Matrix<double, 9, 1>::Constant(NAN)));
	for (size_t i = 0; i < t.gt.objects.size(); ++i)
	{
		io::TObjectGroundTruth& og = t.gt.objects[i];
		const int f = og.first_step;
		if (f < 0 || size_t(f) + 2 >= n) continue;
		// The deterministic centroid velocity (constant: the cars drive straight at their speed).
		const Eigen::Vector2d vdet = (og.features[size_t(f) + 1].rowwise().mean() -
		                              og.features[size_t(f)].rowwise().mean()) /
		                             e;
		// s = [delta; rate; accel] (9: xi-like offset, its rate, its acceleration), 0 up to f + 1
		// where the rate and the acceleration are drawn from the filter's velocity-block prior.
		Eigen::VectorXd s = Eigen::VectorXd::Zero(9);
		for (int a = 0; a < 3; ++a)
		{
			s[6 + a] = p.accel_prior_std[a] * N(g);
			s[3 + a] = 0.5 * e * s[6 + a] + p.velocity_prior_std[a] * N(g);
		}
		for (size_t k = size_t(f) + 1; k < n; ++k)
		{
			if (k > size_t(f) + 1)
			{
				Eigen::VectorXd w(9);
				for (int a = 0; a < 9; ++a) w[a] = N(g);
				s = F * s + L * w;
			}
			Eigen::Matrix2Xd& Fk = og.features[k];
			const Eigen::Vector2d c = Fk.rowwise().mean();
			Fk = (models::rot2(s[2]) * (Fk.colwise() - c)).colwise() + (c + s.head<2>());
			og.visible[k] = (Fk.rowwise().mean() - t.gt.ego[k].head<2>()).norm() <= o.sensor_range;
			og.pose[k] = models::objectPoseInverse(og.features[size_t(f)], Fk);
			auto& x = t.state[i][k];
			x.head<3>() = og.pose[k];
			x.segment<2>(3) = vdet + s.segment<2>(3);
			x[5] = s[5];
			x.tail<3>() = s.tail(3);
		}
	}
	t.gt.checkConsistent();
	return t;
}

struct TRunNees
{
	double ego = 0;                  ///< ego NEES averaged over the gap's steps
	double object = 0;               ///< object NEES [xi; v; a] averaged over its samples
	Eigen::Vector3d parts{0, 0, 0};  ///< the same of xi, v, a alone (3 dof each)
	int objectSamples = 0;
	int initAtSecondSighting = 0;  ///< objects whose velocity block came at f + 1
};

TRunNees runDraw(sim::TScenarioOptions o, uint32_t seed)
{
	o.noise_seed = seed;
	const TCaTruth truth = caTruth(o, seed);
	const io::TGroundTruth& gt = truth.gt;
	const sim::TSimulatedRun run = sim::simulateMeasurements(gt, o, seed);
	CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	mrpt::config::CConfigFileMemory ini;
	dynslam::config::loadIniWithIncludes(DYNSLAM_CONFIG_DIR "/compare_tunnel.ini", ini);
	f.loadOptions(ini);
	f.options.object_model = "ca";
	const double gate = f.options.cv.gate;
	f.options.cv = caParams();
	f.options.cv.gate = gate;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0 = o.Sigma_0;
	f.reset();
	TRunNees r;
	int ne = 0;
	std::map<int32_t, int> since;
	for (size_t k = 0; k < run.actions.size(); ++k)
	{
		f.processActionObservation(run.actions[k], run.frames[k]);
		if (gt.ego[k][0] >= 200 && gt.ego[k][0] <= 800)
		{
			const auto pdf = f.getEgoPose();
			const Eigen::Vector3d d(pdf.mean.x() - gt.ego[k][0], pdf.mean.y() - gt.ego[k][1],
			                        models::wrapToPi(pdf.mean.phi() - gt.ego[k][2]));
			r.ego += d.dot(pdf.cov.asEigen().ldlt().solve(d));
			++ne;
		}
		Eigen::VectorXd x;
		Eigen::MatrixXd P;
		std::vector<std::string> labels;
		f.getStateWithoutPads(x, P, &labels);
		// object -> entries of its pose of this step (3) and of its velocity block (6)
		std::map<int32_t, std::vector<int>> xiIdx, vIdx;
		for (size_t j = 0; j < labels.size(); ++j)
		{
			int obj = -1, step = -1;
			char c = 0;
			if (std::sscanf(labels[j].c_str(), "obj%d.xi%d.%c", &obj, &step, &c) == 3 &&
			    step == int(k))
				xiIdx[obj].push_back(int(j));
			else if (std::sscanf(labels[j].c_str(), "obj%d.v%d.", &obj, &step) == 2)
			{
				vIdx[obj].push_back(int(j));
				since[obj] = step;
			}
		}
		std::map<int32_t, std::vector<int>> idx;  // object -> [xi; v; a]
		for (const auto& [obj, iv] : vIdx)
		{
			idx[obj] = xiIdx[obj];
			idx[obj].insert(idx[obj].end(), iv.begin(), iv.end());
		}
		for (const auto& [obj, id] : idx)
		{
			if (id.size() != 9) continue;  // no velocity block yet (or not a 3-dof pose)
			const Eigen::Matrix<double, 9, 1>& xt = truth.state[size_t(obj)][k];
			if (!xt.allFinite()) continue;
			Eigen::VectorXd d = x(id) - xt;
			d[2] = models::wrapToPi(d[2]);
			const Eigen::MatrixXd Pi = P(id, id);
			r.object += d.dot(Pi.ldlt().solve(d));
			for (int b = 0; b < 3; ++b)
			{
				const Eigen::Vector3d db = d.segment<3>(3 * b);
				r.parts[b] += db.dot(Pi.block<3, 3>(3 * b, 3 * b).ldlt().solve(db));
			}
			++r.objectSamples;
		}
	}
	for (const auto& [obj, s] : since)
		if (s == gt.objects[size_t(obj)].first_step + 1) ++r.initAtSecondSighting;
	r.ego /= ne;
	r.object /= r.objectSamples;
	r.parts /= r.objectSamples;
	return r;
}
}  // namespace

TEST(ObjectModelCaConsistency, ModelMatchedTunnelNeesInsideChiSquareBounds)
{
	// 300 draws, seeds 940001... Each run's mean is an average of NEES samples of k dof (mean k if
	// consistent; its variance at most a single sample's), so the bounds of 300 independent
	// samples, chi2(300 k) / 300, are valid on the wide side. 95 % two-sided (z = 1.96).
	const int runs = 300;
	sim::TScenarioOptions o = sim::loadScenario(DYNSLAM_DATASETS_DIR "/tunnel_scenario.ini");
	o.start_from_prior = true;
	TRunNees m;
	int samples = 0, inits = 0;
	for (int i = 0; i < runs; ++i)
	{
		const TRunNees r = runDraw(o, 940001u + uint32_t(i));
		m.ego += r.ego / runs;
		m.object += r.object / runs;
		m.parts += r.parts / runs;
		samples += r.objectSamples;
		inits += r.initAtSecondSighting;
	}
	const auto [lo9, hi9] = chi2Bounds(9.0 * runs, 1.96);
	const auto [lo3, hi3] = chi2Bounds(3.0 * runs, 1.96);
	std::printf(
	    "[ measured ] %d draws, %d object samples: object NEES [xi; v; a] %.3f in [%.3f, %.3f] "
	    "(xi %.3f, v %.3f, a %.3f; 3-dof bounds [%.3f, %.3f]); ego gap NEES %.3f\n",
	    runs, samples, m.object, lo9 / runs, hi9 / runs, m.parts[0], m.parts[1], m.parts[2],
	    lo3 / runs, hi3 / runs, m.ego);
	EXPECT_EQ(inits, 2 * runs);  // both cars get their velocity at their second sighting
	EXPECT_GT(samples, 2 * runs * 100);
	EXPECT_GT(m.object, lo9 / runs);
	EXPECT_LT(m.object, hi9 / runs);
	for (int b = 0; b < 3; ++b)
	{
		EXPECT_GT(m.parts[b], lo3 / runs) << "block " << b;
		EXPECT_LT(m.parts[b], hi3 / runs) << "block " << b;
	}
	EXPECT_GT(m.ego, lo3 / runs);
	EXPECT_LT(m.ego, hi3 / runs);
}
