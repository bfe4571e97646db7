/** End to end on the shipped excerpt (datasets/mrclam/MRCLAM_Dataset6_excerpt, robot 3,
 * first 121 s of Dataset 6): import with config/mrclam.ini, then read everything back. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/io/ground_truth.h>
#include <dynslam/mrclam/CMrclamOptions.h>
#include <dynslam/mrclam/import.h>
#include <dynslam/mrclam/odometry.h>
#include <dynslam/mrclam/rawlog_writer.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "mini_dataset.h"

using namespace dynslam::mrclam;

namespace
{
const std::string kExcerpt = std::string(DYNSLAM_DATASETS_DIR) + "/mrclam/MRCLAM_Dataset6_excerpt";
constexpr int kEgo = 3;

TMrclamOptions configOptions()
{
	mrpt::config::CConfigFile ini(std::string(DYNSLAM_CONFIG_DIR) + "/mrclam.ini");
	TMrclamOptions o;
	o.loadFromConfigFile(ini, "MRCLAM_Import");
	return o;
}

/** Rows of a .dat file without comments, split on whitespace (independent of the library). */
std::vector<std::vector<std::string>> rawRows(const std::string& path)
{
	std::ifstream f(path);
	std::vector<std::vector<std::string>> out;
	std::string s;
	while (std::getline(f, s))
	{
		if (s.empty() || s[0] == '#') continue;
		std::istringstream is(s);
		std::vector<std::string> toks;
		std::string t;
		while (is >> t) toks.push_back(t);
		if (!toks.empty()) out.push_back(toks);
	}
	return out;
}

/** Imports the excerpt once and writes it into a temp dir. */
struct TFixture
{
	TImportResult res;
	std::string dir;
	TFixture()
	{
		const auto opts = configOptions();
		res = importRobot(loadDataset(kExcerpt, kEgo), opts.import);
		dir = mrclam_test::tempDir("excerpt");
		writeImport(res, opts, dir, "robot3");
	}
};
const TFixture& fixture()
{
	static TFixture f;
	return f;
}
}  // namespace

TEST(MrclamExcerpt, ConfigFileAndBuiltInDefaultsAgree)
{
	const TMrclamOptions def, cfg = configOptions();
	std::ostringstream a, b;
	def.dumpToTextStream(a);
	cfg.dumpToTextStream(b);
	EXPECT_EQ(a.str(), b.str());
}

TEST(MrclamExcerpt, MeasurementCountsPerSubjectMatchTheRawFile)
{
	const auto& s = fixture().res.summary;
	// independent count from the raw text files
	std::map<int, int> barcodeToSubject;
	for (const auto& r : rawRows(kExcerpt + "/Barcodes.dat"))
		barcodeToSubject[std::stoi(r[1])] = std::stoi(r[0]);
	std::map<int, size_t> counts;
	size_t rows = 0, unknown = 0;
	for (const auto& r : rawRows(kExcerpt + "/Robot3_Measurement.dat"))
	{
		rows++;
		const auto it = barcodeToSubject.find(std::stoi(r[1]));
		if (it == barcodeToSubject.end())
			unknown++;
		else
			counts[it->second]++;
	}
	ASSERT_GT(rows, 500u);
	EXPECT_EQ(s.rows, rows);
	EXPECT_EQ(s.spurious, unknown);
	EXPECT_EQ(s.outside_window + s.duplicates + s.own_barcode, 0u);
	EXPECT_EQ(s.per_subject, counts);
	EXPECT_EQ(s.kept, rows - unknown);
	// all four other robots and all 15 landmarks are measured in the excerpt
	size_t robots = 0, landmarks = 0;
	for (const auto& [subj, c] : counts) (isRobotSubject(subj) ? robots : landmarks) += c > 0;
	EXPECT_EQ(robots, 4u);
	EXPECT_EQ(landmarks, 15u);
	EXPECT_GT(s.duration(), 115.0);
}

TEST(MrclamExcerpt, RawlogReadsBackWithCRawlog)
{
	const auto& f = fixture();
	mrpt::obs::CRawlog log;
	ASSERT_TRUE(log.loadFromRawLogFile(f.dir + "/robot3.rawlog"));
	const size_t K = f.res.steps.size();
	ASSERT_EQ(log.size(), 2 * K);
	std::map<int, size_t> perSubject;
	for (size_t k = 0; k < K; k++)
	{
		ASSERT_EQ(log.getType(2 * k), mrpt::obs::CRawlog::etActionCollection);
		ASSERT_EQ(log.getType(2 * k + 1), mrpt::obs::CRawlog::etSensoryFrame);
		const auto acts = log.getAsAction(2 * k);
		const auto mv = acts->getActionByClass<mrpt::obs::CActionRobotMovement2D>();
		ASSERT_TRUE(mv);
		const auto* g = dynamic_cast<const mrpt::poses::CPosePDFGaussian*>(mv->poseChange.get());
		ASSERT_NE(g, nullptr);
		if (k == 0)
		{
			EXPECT_EQ(g->mean.norm(), 0.0);
			EXPECT_EQ(g->mean.phi(), 0.0);
			EXPECT_EQ(g->cov.asEigen().norm(), 0.0);
		}
		else
		{
			EXPECT_GT(g->cov(0, 0), 0.0);
			EXPECT_GT(g->cov(2, 2), 0.0);
		}
		const auto sf = log.getAsObservations(2 * k + 1);
		ASSERT_EQ(sf->size(), 1u);
		const auto obs = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		ASSERT_TRUE(obs);
		EXPECT_EQ(obs->sensorLabel, "RB");
		EXPECT_FLOAT_EQ(obs->maxSensorDistance, 10.0f);
		EXPECT_FLOAT_EQ(obs->fieldOfView_yaw, static_cast<float>(2 * M_PI));
		EXPECT_EQ(obs->fieldOfView_pitch, 0.0f);
		EXPECT_NEAR(mrpt::Clock::toDouble(obs->timestamp), f.res.steps[k].t, 1e-6);
		ASSERT_EQ(obs->sensedData.size(), f.res.steps[k].meas.size());
		for (const auto& m : obs->sensedData)
		{
			EXPECT_EQ(m.pitch, 0.0f);
			const int subject = dynslam::ids::isStatic(m.landmarkID)
			                        ? m.landmarkID
			                        : dynslam::ids::objectOf(m.landmarkID);
			if (dynslam::ids::isObjectFeature(m.landmarkID))
			{
				EXPECT_EQ(dynslam::ids::featureOf(m.landmarkID), 0);
				EXPECT_TRUE(isRobotSubject(subject));
			}
			else
				EXPECT_TRUE(isLandmarkSubject(subject));
			EXPECT_NE(subject, kEgo);
			perSubject[subject]++;
		}
	}
	EXPECT_EQ(perSubject, f.res.summary.per_subject);
}

TEST(MrclamExcerpt, GroundTruthReadsBackAndMatchesTheSteps)
{
	const auto& f = fixture();
	const auto gt = dynslam::io::readGroundTruth(f.dir, "robot3");
	const size_t K = f.res.steps.size();
	ASSERT_EQ(gt.numSteps(), K);
	EXPECT_EQ(gt.landmarks.size(), 15u);
	EXPECT_NEAR(gt.ego[0].norm(), 0.0, 1e-12);  // world frame = ego pose at step 0
	ASSERT_EQ(gt.objects.size(), 6u);  // index = subject 0..5; 0 and the ego are placeholders
	for (const auto& o : gt.objects)
	{
		EXPECT_EQ(o.num_features, 1);
		if (o.object == 0 || o.object == kEgo)
		{
			EXPECT_EQ(o.first_step, -1);
			continue;
		}
		int first = -1;
		for (size_t k = 0; k < K; k++)
		{
			bool measured = false;
			for (const auto& m : f.res.steps[k].meas) measured |= (m.subject == o.object);
			EXPECT_EQ(bool(o.visible[k]), measured) << "object " << o.object << " step " << k;
			if (measured && first < 0) first = int(k);
			ASSERT_TRUE(o.features[k].allFinite());
		}
		EXPECT_EQ(o.first_step, first);
		ASSERT_GE(first, 0);
		EXPECT_NEAR(o.pose[first].norm(), 0.0, 1e-12);
		const Eigen::Vector2d d = o.features[K - 1].col(0) - o.features[first].col(0);
		EXPECT_NEAR((o.pose[K - 1].head<2>() - d).norm(), 0.0, 1e-9);
		EXPECT_EQ(o.pose[K - 1].z(), 0.0);
	}
	// a measured range agrees with the ground-truth geometry (median residual over all)
	std::vector<double> res;
	for (size_t k = 0; k < K; k++)
		for (const auto& m : f.res.steps[k].meas)
		{
			const Eigen::Vector2d q =
			    isLandmarkSubject(m.subject)
			        ? gt.landmarks.at(m.subject)
			        : Eigen::Vector2d(gt.objects[m.subject].features[k].col(0));
			res.push_back(std::abs((q - gt.ego[k].head<2>()).norm() - m.range));
		}
	std::nth_element(res.begin(), res.begin() + res.size() / 2, res.end());
	EXPECT_LT(res[res.size() / 2], 0.15);  // median |range error| [m]
}

/** Dead reckoning from the rawlog's actions (means composed, covariance propagated) against
 * the ground truth. */
TEST(MrclamExcerpt, DeadReckoningFollowsTheGroundTruthAtTheStart)
{
	const auto& f = fixture();
	mrpt::obs::CRawlog log;
	ASSERT_TRUE(log.loadFromRawLogFile(f.dir + "/robot3.rawlog"));
	const auto gt = dynslam::io::readGroundTruth(f.dir, "robot3");
	Eigen::Vector3d x = Eigen::Vector3d::Zero();
	Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
	const double t0 = gt.t[0];
	std::map<int, double> errAt, sigmaAt, pathAt;  // last step at or before 10, 20, ... s
	double path = 0;                               // ground-truth path length [m]
	size_t n = 0, inside = 0;
	for (size_t k = 0; 2 * k + 1 < log.size(); k++)
	{
		const auto mv =
		    log.getAsAction(2 * k)->getActionByClass<mrpt::obs::CActionRobotMovement2D>();
		const auto* g = dynamic_cast<const mrpt::poses::CPosePDFGaussian*>(mv->poseChange.get());
		const Eigen::Vector3d u(g->mean.x(), g->mean.y(), g->mean.phi());
		const double c = std::cos(x.z()), s = std::sin(x.z());
		Eigen::Matrix3d F = Eigen::Matrix3d::Identity(), G = Eigen::Matrix3d::Identity();
		F(0, 2) = -s * u.x() - c * u.y();
		F(1, 2) = c * u.x() - s * u.y();
		G.topLeftCorner<2, 2>() << c, -s, s, c;
		P = F * P * F.transpose() + G * g->cov.asEigen() * G.transpose();
		x = composeSE2(x, u);
		const double t = gt.t[k] - t0;
		const Eigen::Vector2d e = x.head<2>() - gt.ego[k].head<2>();
		if (k > 0) path += (gt.ego[k].head<2>() - gt.ego[k - 1].head<2>()).norm();
		for (int T = 10; T <= 120; T += 10)
			if (t <= T)
			{
				errAt[T] = e.norm();
				sigmaAt[T] = std::sqrt(P(0, 0) + P(1, 1));
				pathAt[T] = path;
			}
		if (t <= 60.0 && k > 0)
		{
			// inside the 99.9 % ellipse of the propagated odometry covariance (chi2, 2 dof)
			n++;
			inside += e.dot(P.topLeftCorner<2, 2>().inverse() * e) <= 13.82;
		}
	}
	std::cout << "dead reckoning from the rawlog (time: position error / model sigma / path "
	             "length) [s: m / m / m]:\n";
	for (const auto& [T, e] : errAt)
		std::cout << "  " << T << ": " << e << " / " << sigmaAt[T] << " / " << pathAt[T] << "\n";
	std::cout << inside << " of " << n << " steps of the first 60 s inside the 99.9% ellipse\n";
	ASSERT_GT(n, 100u);
	// The bound (doc/results/real-data.md): at the start of the run (10 s, 30 s) the position error
	// is below 15 % of the ground-truth path length plus 2 cm (Vicon and interpolation floor);
	// after 60 s below 25 %. Measured: 4.3 %, 13.6 %, 20.1 % (robot 3 is not the best robot of
	// Dataset 6 for dead reckoning, nor the worst).
	for (int T : {10, 30, 60})
	{
		ASSERT_GT(pathAt[T], 0.3) << "the robot must have moved";
		EXPECT_LT(errAt[T], 0.02 + (T <= 30 ? 0.15 : 0.25) * pathAt[T]) << "after " << T << " s";
	}
	// The per-step noise model is fitted to independent per-step errors; over tens of seconds
	// the errors are correlated (heading bias), so the propagated covariance is overconfident
	// there (doc/results/real-data.md). It still holds for most steps of the first minute:
	EXPECT_GE(inside, n * 80 / 100);
}
