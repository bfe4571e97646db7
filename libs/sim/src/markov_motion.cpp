/** @file markov_motion.cpp
 * Markov-switching object motion (markov_motion.h) and the [ObjectMotion] section of the
 * scenario INI (strict reading, effective-configuration writer). */
#include <dynslam/common/config_utils.h>
#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/markov_motion.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/random/RandomGenerators.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "options_format.h"
#include "options_sections.h"

namespace dynslam::sim
{
namespace
{
const std::vector<std::string> kModeNames{"stationary", "cv", "turn", "manoeuvre"};

/** A square root L (L L^T = Q) of a PSD process noise: the rows/columns of zero-noise axes
 * are skipped (Q = 0 there), so a zero PSD on an axis is allowed. */
Eigen::MatrixXd noiseRoot(const Eigen::MatrixXd& Q)
{
	Eigen::MatrixXd L = Eigen::MatrixXd::Zero(Q.rows(), Q.cols());
	const Eigen::Index d = Q.rows() / 2;
	for (Eigen::Index i = 0; i < d; ++i)
	{
		const double q11 = Q(i, i), q21 = Q(d + i, i), q22 = Q(d + i, d + i);
		if (!(q11 > 0)) continue;  // this axis has no noise
		L(i, i) = std::sqrt(q11);
		L(d + i, i) = q21 / L(i, i);
		L(d + i, d + i) = std::sqrt(std::max(0.0, q22 - L(d + i, i) * L(d + i, i)));
	}
	return L;
}
}  // namespace

std::string markovModeName(int mode)
{
	if (mode < 0 || mode >= kMarkovModeCount)
		throw std::out_of_range("markovModeName: no mode " + std::to_string(mode));
	return kModeNames[size_t(mode)];
}

Eigen::VectorXd markovModeStep(int mode, const Eigen::VectorXd& s, double dt)
{
	if (s.size() != 4 && s.size() != 6)
		throw std::invalid_argument("markovModeStep: s must have 4 or 6 entries");
	switch (mode)
	{
		case 0:
		{
			Eigen::VectorXd out = s;
			out.tail(s.size() / 2).setZero();
			return out;
		}
		case 1:
		case 3:
			return models::cvPredict(s, dt);
		case 2:
			return models::ctrvPredict(s, dt);
		default:
			throw std::out_of_range("markovModeStep: no mode " + std::to_string(mode));
	}
}

Eigen::MatrixXd markovModeNoise(int mode, const TObjectMotionOptions& m, int d, double dt)
{
	if (mode < 0 || mode >= kMarkovModeCount)
		throw std::out_of_range("markovModeNoise: no mode " + std::to_string(mode));
	const Eigen::Vector3d& q = mode == 3 ? m.manoeuvre_psd : m.accel_psd;
	return models::cvProcessNoise(q.head(d), dt);
}

std::vector<TMarkovTrack> markovObjectTracks(const TScenarioOptions& o,
                                             const std::vector<Eigen::VectorXd>& s0)
{
	const TObjectMotionOptions& m = o.object_motion;
	if (!m.markov)
		throw std::invalid_argument("markovObjectTracks: [ObjectMotion] model is not markov");
	const Eigen::MatrixXd Pi = models::uniformSwitching(kMarkovModeCount, m.switch_prob);
	mrpt::random::CRandomGenerator rng(uint32_t(o.noise_seed + 0xB5297A4Du));
	std::vector<TMarkovTrack> out(s0.size());
	for (size_t i = 0; i < s0.size(); ++i)
	{
		const Eigen::Index n = s0[i].size();
		if (n != 4 && n != 6)
			throw std::invalid_argument("markovObjectTracks: object " + std::to_string(i) +
			                            ": the state must have 4 or 6 entries");
		const int d = int(n / 2);
		std::vector<Eigen::MatrixXd> L;
		for (int j = 0; j < kMarkovModeCount; ++j)
			L.push_back(noiseRoot(markovModeNoise(j, m, d, o.dt)));
		TMarkovTrack& t = out[i];
		t.mode.assign(o.numSteps(), m.initial_mode);
		t.state.assign(o.numSteps(), s0[i]);
		for (size_t k = 1; k < o.numSteps(); ++k)
		{
			// The switch: the inverse CDF of row mode[k-1] of Pi at one uniform draw.
			const double u = rng.drawUniform(0.0, 1.0);
			int next = kMarkovModeCount - 1;
			double cum = 0;
			for (int j = 0; j < kMarkovModeCount; ++j)
				if (u < (cum += Pi(t.mode[k - 1], j)))
				{
					next = j;
					break;
				}
			t.mode[k] = next;
			Eigen::VectorXd w(n);
			for (Eigen::Index a = 0; a < n; ++a) w[a] = rng.drawGaussian1D_normalized();
			Eigen::VectorXd s = markovModeStep(next, t.state[k - 1], o.dt) + L[size_t(next)] * w;
			if (d == 3) s[2] = models::wrapToPi(s[2]);
			t.state[k] = s;
		}
	}
	return out;
}

namespace detail
{
namespace cfg = dynslam::config;

void readObjectMotion(const mrpt::config::CConfigFileBase& c, TScenarioOptions& o)
{
	const std::string S = "ObjectMotion";
	cfg::rejectUnknownKeys(c, S,
	                       {"model", "switch_prob", "accel_psd", "manoeuvre_psd", "initial_mode"});
	TObjectMotionOptions& m = o.object_motion;
	m = TObjectMotionOptions();
	m.markov = cfg::readChoice(c, S, "model", {"deterministic", "markov"}, 0) == 1;
	if (!m.markov)
	{
		for (const char* k : {"switch_prob", "accel_psd", "manoeuvre_psd", "initial_mode"})
			if (cfg::has(c, S, k))
				cfg::fail(S, k, cfg::readString(c, S, k, ""), "only with model = markov");
		return;
	}
	m.switch_prob = cfg::readNonNegative(c, S, "switch_prob", 0, true);
	if (!(m.switch_prob < 1)) cfg::fail(S, "switch_prob", fmt(m.switch_prob), "must be in [0, 1)");
	for (const char* k : {"accel_psd", "manoeuvre_psd"})
	{
		const Eigen::Vector3d q = cfg::readVector(c, S, k, Eigen::Vector3d::Zero(), 3, true);
		if (!q.allFinite() || (q.array() < 0).any())
			cfg::fail(S, k, fmtMatrix(q.transpose()), "must be finite and >= 0");
		(std::string(k) == "accel_psd" ? m.accel_psd : m.manoeuvre_psd) = q;
	}
	m.initial_mode = cfg::readChoice(c, S, "initial_mode", kModeNames, 1);
	if (!o.object_accel_psd.isZero())
		cfg::fail(S, "model", "markov",
		          "conflicts with [Noise] object_accel_psd (set one of the two object truths)");
}

void dumpObjectMotion(std::ostream& out, const TObjectMotionOptions& m)
{
	if (!m.markov) return;
	out << "\n[ObjectMotion]\n";
	out << "model = markov\n";
	out << "switch_prob = " << fmt(m.switch_prob) << "\n";
	out << "accel_psd = " << fmtMatrix(m.accel_psd.transpose()) << "\n";
	out << "manoeuvre_psd = " << fmtMatrix(m.manoeuvre_psd.transpose()) << "\n";
	out << "initial_mode = " << kModeNames[size_t(m.initial_mode)] << "\n";
}
}  // namespace detail
}  // namespace dynslam::sim
