/** Linear-Gaussian case: heading known and constant (zero heading variance and noise), the
 * Cartesian model is then linear in positions, and one-feature objects have linear
 * (translation-only) poses. The filter must equal the batch least-squares solution of the same
 * data, marginalised to the variables the filter keeps. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <Eigen/Dense>

#include "tiny_scenario.h"

using namespace dynslam;

namespace
{
/** Linear residuals r = r0 + sum J v of 2-vector variables (offsets into the stacked state). */
struct TBatch
{
	struct TResidual
	{
		std::vector<std::pair<int, Eigen::Matrix2d>> J;  // d r / d var
		Eigen::Vector2d r0;                              // r = r0 + sum J v
		Eigen::Matrix2d S;
	};
	std::map<std::string, int> var;  ///< variable name -> offset
	std::vector<TResidual> res;

	/** Offset of the variable, added at the end if new. */
	int idx(const std::string& name)
	{
		auto it = var.find(name);
		if (it != var.end()) return it->second;
		const int i = 2 * int(var.size());
		var[name] = i;
		return i;
	}
};

/** Batch residuals of the data. Variables: p_0..p_N, every static landmark, every object's f0,
 * f_t and xi_t per step. */
void buildBatch(const dynslam_test::TinyScenario& sc, const dynslam_test::TinyScenarioOptions& o,
                const Eigen::Matrix2d& Sxi, const Eigen::Matrix2d& S0, TBatch& b)
{
	auto idx = [&](const std::string& name) { return b.idx(name); };
	auto& res = b.res;
	const int N = int(sc.actions.size());
	const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
	res.push_back({{{idx("p0"), I}}, Eigen::Vector2d::Zero(), S0});  // p0 ~ N(0, S0)
	std::map<int32_t, int> firstSeen;
	for (int k = 0; k < N; ++k)
	{
		const std::string pk = "p" + std::to_string(k);
		if (k > 0)
		{
			mrpt::poses::CPose2D u;
			sc.actions[k]->getBestMovementEstimation()->poseChange->getMean(u);
			ASSERT_EQ(u.phi(), 0.0);
			// p_k - p_{k-1} - u = 0
			res.push_back({{{idx(pk), I}, {idx("p" + std::to_string(k - 1)), -I}},
			               -Eigen::Vector2d(u.x(), u.y()),
			               o.Sigma_w.topLeftCorner<2, 2>()});
		}
		const auto obs = sc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		for (const auto& m : obs->sensedData)
		{
			const Eigen::Vector2d z =
			    models::fromRangeBearing(models::MeasurementModel::Cartesian, m.range, m.yaw);
			std::string fv;
			if (ids::isStatic(m.landmarkID))
				fv = "l" + std::to_string(m.landmarkID);
			else
			{
				const int a = ids::objectOf(m.landmarkID);
				const bool first = !firstSeen.count(a);
				if (first) firstSeen[a] = k;
				fv = first ? "o" + std::to_string(a) + "f0"
				           : "o" + std::to_string(a) + "ft" + std::to_string(k);
				if (!first)  // xi_t - (f_t - f_0) = 0, Sigma_xi
					res.push_back({{{idx("o" + std::to_string(a) + "xi" + std::to_string(k)), I},
					                {idx(fv), -I},
					                {idx("o" + std::to_string(a) + "f0"), I}},
					               Eigen::Vector2d::Zero(),
					               Sxi});
			}
			// z - (f - p_k) = 0  ->  r = (f - p_k) - z
			res.push_back({{{idx(fv), I}, {idx(pk), -I}}, -z, o.Sigma_v});
		}
	}
}

/** Dense information form of the batch: Sigma = Lambda^-1, mu = Sigma eta. */
void solveBatch(const TBatch& b, Eigen::VectorXd& mu, Eigen::MatrixXd& Sigma)
{
	const int n = 2 * int(b.var.size());
	Eigen::MatrixXd Lambda = Eigen::MatrixXd::Zero(n, n);
	Eigen::VectorXd eta = Eigen::VectorXd::Zero(n);
	for (const auto& r : b.res)
	{
		const Eigen::Matrix2d W = r.S.inverse();
		for (const auto& [i, Ji] : r.J)
		{
			eta.segment<2>(i) -= Ji.transpose() * W * r.r0;
			for (const auto& [j, Jj] : r.J) Lambda.block<2, 2>(i, j) += Ji.transpose() * W * Jj;
		}
	}
	Sigma = Lambda.inverse();
	mu = Sigma * eta;
}

/** Filter state indices (heading excluded) and the matching batch offsets, from the filter's
 * state labels; the ego is the last pose p_{N-1}. */
void matchIndices(const std::vector<std::string>& labels, const std::map<std::string, int>& var,
                  int N, std::vector<int>& fIdx, std::vector<int>& bIdx)
{
	fIdx = {0, 1};
	bIdx = {var.at("p" + std::to_string(N - 1)), var.at("p" + std::to_string(N - 1)) + 1};
	for (size_t i = 3; i < labels.size(); i += 2)
	{
		const std::string& L = labels[i];
		std::string b;
		if (L.rfind("lm", 0) == 0)
			b = "l" + L.substr(2, L.find('.') - 2);
		else
		{
			const std::string obj = L.substr(3, L.find('.') - 3);
			if (L.find(".f0.t0") != std::string::npos)
				b = "o" + obj + "f0";
			else if (L.find(".xi") != std::string::npos)
				b = "o" + obj + "xi" +
				    L.substr(L.find(".xi") + 3, L.find(".dx") - L.find(".xi") - 3);
			else
				FAIL() << "unexpected label " << L;
		}
		ASSERT_TRUE(var.count(b)) << b;
		fIdx.insert(fIdx.end(), {int(i), int(i + 1)});
		bIdx.insert(bIdx.end(), {var.at(b), var.at(b) + 1});
	}
}
}  // namespace

TEST(DynamicLinearGaussian, FilterEqualsBatchLeastSquares)
{
	dynslam_test::TinyScenarioOptions o;
	o.steps = 14;
	o.landmarks = 6;
	o.objects = 2;
	o.features_per_object = 1;
	o.range = 40;
	o.u = Eigen::Vector3d(0.7, 0.0, 0.0);
	o.Sigma_w = Eigen::Vector3d(2e-3, 1e-3, 0.0).asDiagonal();
	o.cartesian_noise = true;
	o.Sigma_v = (Eigen::Matrix2d() << 2e-3, 5e-4, 5e-4, 1e-3).finished();
	o.seed = 7;
	auto sc = dynslam_test::makeTinyScenario(o);
	// Heading noise is zero, so the odometry heading is exactly 0: the model is linear.
	const Eigen::Matrix2d Sxi = (Eigen::Matrix2d() << 0.05, 0.01, 0.01, 0.03).finished();
	const Eigen::Matrix2d S0 = Eigen::Vector2d(1e-3, 2e-3).asDiagonal();

	CDynamicKFSLAM2D f;
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_xi = Sxi;
	f.options.Sigma_0.setZero();
	f.options.Sigma_0.topLeftCorner<2, 2>() = S0;
	f.options.keep_last_poses = 1;
	f.reset();
	for (size_t k = 0; k < sc.actions.size(); ++k)
		f.processActionObservation(sc.actions[k], sc.frames[k]);

	// ---- Batch least squares, dense information form ------------------------------------
	TBatch batch;
	ASSERT_NO_FATAL_FAILURE(buildBatch(sc, o, Sxi, S0, batch));
	Eigen::VectorXd mu;
	Eigen::MatrixXd Sigma;
	solveBatch(batch, mu, Sigma);

	// ---- Compare with the filter's variables ---------------------------------------------
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	std::vector<std::string> labels;
	f.getStateWithoutPads(x, P, &labels);
	std::vector<int> fIdx, bIdx;  // filter index, batch index (heading excluded)
	ASSERT_NO_FATAL_FAILURE(matchIndices(labels, batch.var, int(sc.actions.size()), fIdx, bIdx));
	const Eigen::VectorXd xf = x(fIdx), xb = mu(bIdx);
	const Eigen::MatrixXd Pf = P(fIdx, fIdx), Pb = Sigma(bIdx, bIdx);
	EXPECT_GT(fIdx.size(), 14u);
	EXPECT_LT((xf - xb).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, xb.cwiseAbs().maxCoeff()));
	EXPECT_LT((Pf - Pb).cwiseAbs().maxCoeff(), 1e-9 * Pb.cwiseAbs().maxCoeff());
	// Heading stays exactly known.
	EXPECT_EQ(x[2], 0.0);
	EXPECT_EQ(P(2, 2), 0.0);
}
