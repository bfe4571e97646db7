#include <dynslam/core/chi2.h>
#include <dynslam/core/models/assignment.h>
#include <dynslam/core/models/bev_box.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/box_tracker.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dynslam::estimator
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

void require(bool ok, const char* what)
{
	if (!ok) throw std::invalid_argument(std::string("TBoxTrackerParams: ") + what);
}

bool positive(double v) { return std::isfinite(v) && v > 0; }

/** The box noise: meas_std^2 on the diagonal, the caller's centre covariance added. */
Matrix5d boxNoise(const TBoxTrackerParams& p, const TWorldBox& b)
{
	Matrix5d R = p.meas_std.cwiseAbs2().asDiagonal();
	R.topLeftCorner<2, 2>() += b.centre_cov;
	return R;
}

bool symmetric(const Eigen::Matrix2d& m)
{
	return std::abs(m(0, 1) - m(1, 0)) <= 1e-9 * (std::abs(m(0, 1)) + std::abs(m(1, 0)) + 1e-300);
}

void checkBox(const TWorldBox& b, size_t i)
{
	const bool finite = b.pose.allFinite() && b.extent.allFinite() && b.centre_cov.allFinite();
	const bool ok =
	    finite && !std::isnan(b.score) && b.extent.minCoeff() > 0 && symmetric(b.centre_cov) &&
	    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(b.centre_cov).eigenvalues().minCoeff() >= 0;
	if (!ok)
		throw std::invalid_argument(
		    "CBoxTracker::update: box " + std::to_string(i) +
		    " needs a finite pose, length and width > 0, a score that is not NaN and a finite "
		    "symmetric positive semi-definite centre_cov");
}

models::TBevBox footprint(const Eigen::Vector3d& pose, const Eigen::Vector2d& extent)
{
	return {pose.x(), pose.y(), pose.z(), extent.x(), extent.y()};
}
}  // namespace

void TBoxTrackerParams::validate() const
{
	require(metric == "mahalanobis" || metric == "bev_iou",
	        "metric must be \"mahalanobis\" or \"bev_iou\"");
	require(gate_prob > 0 && gate_prob < 1, "gate_prob must be in (0, 1)");
	require(min_iou > 0 && min_iou <= 1, "min_iou must be in (0, 1]");
	require(min_hits >= 1, "min_hits must be >= 1");
	require(birth_window >= min_hits, "birth_window must be >= min_hits");
	require(max_age >= 1, "max_age must be >= 1");
	require(!std::isnan(min_score), "min_score must not be NaN");
	require(positive(accel_std), "accel_std must be finite and > 0");
	require(positive(yaw_std), "yaw_std must be finite and > 0");
	require(positive(extent_std), "extent_std must be finite and > 0");
	require(positive(velocity_std), "velocity_std must be finite and > 0");
	require(meas_std.allFinite() && meas_std.minCoeff() > 0,
	        "meas_std must be finite and > 0 (each of x, y, yaw, length, width)");
}

CBoxTracker::CBoxTracker(const TBoxTrackerParams& params) : m_params(params)
{
	m_params.validate();
}

void CBoxTracker::predict(double dt)
{
	if (!(std::isfinite(dt) && dt > 0))
		throw std::invalid_argument("CBoxTracker::predict: dt must be finite and > 0");
	Matrix7d F = Matrix7d::Identity();
	F(0, 5) = F(1, 6) = dt;
	Matrix7d Q = Matrix7d::Zero();
	const double qa = m_params.accel_std * m_params.accel_std;
	for (int i = 0; i < 2; ++i)
	{
		Q(i, i) = qa * std::pow(dt, 4) / 4;
		Q(i, 5 + i) = Q(5 + i, i) = qa * std::pow(dt, 3) / 2;
		Q(5 + i, 5 + i) = qa * dt * dt;
	}
	Q(2, 2) = m_params.yaw_std * m_params.yaw_std;
	Q(3, 3) = Q(4, 4) = m_params.extent_std * m_params.extent_std;
	for (TBoxTrack& t : m_tracks)
	{
		t.x = F * t.x;
		t.x(2) = models::wrapToPi(t.x(2));
		t.P = F * t.P * F.transpose() + Q;
		t.P = (0.5 * (t.P + t.P.transpose())).eval();
	}
}

void CBoxTracker::overridePrediction(int32_t id, const Eigen::Vector2d& centre,
                                     const Eigen::Matrix2d& cov)
{
	TBoxTrack* t = nullptr;
	for (TBoxTrack& k : m_tracks)
		if (k.id == id) t = &k;
	if (t == nullptr)
		throw std::invalid_argument("CBoxTracker::overridePrediction: unknown track " +
		                            std::to_string(id));
	const Eigen::LLT<Eigen::Matrix2d> llt(cov);
	if (!centre.allFinite() || !cov.allFinite() || !symmetric(cov) || llt.info() != Eigen::Success)
		throw std::invalid_argument(
		    "CBoxTracker::overridePrediction: the centre must be finite and its covariance "
		    "symmetric positive definite");
	// Jeffrey's rule: p'(c) p(r | c). G = P_rc P_cc^-1 (r: the 5 other states).
	const Eigen::Matrix2d Pcc = t->P.topLeftCorner<2, 2>();
	const Eigen::Matrix<double, 5, 2> Prc = t->P.bottomLeftCorner<5, 2>();
	const Eigen::Matrix<double, 5, 2> G = Pcc.llt().solve(Prc.transpose()).transpose();
	const Eigen::Vector2d dc = centre - t->x.head<2>();
	t->x.tail<5>() += G * dc;
	t->x.head<2>() = centre;
	t->x(2) = models::wrapToPi(t->x(2));
	const Eigen::Matrix<double, 5, 5> Prr = t->P.bottomRightCorner<5, 5>();
	t->P.bottomRightCorner<5, 5>() = Prr - G * Prc.transpose() + G * cov * G.transpose();
	t->P.bottomLeftCorner<5, 2>() = G * cov;
	t->P.topRightCorner<2, 5>() = (G * cov).transpose();
	t->P.topLeftCorner<2, 2>() = cov;
	t->P = (0.5 * (t->P + t->P.transpose())).eval();
}

Eigen::MatrixXd CBoxTracker::costs(const std::vector<TWorldBox>& boxes) const
{
	const bool iou = m_params.metric == "bev_iou";
	const double gate = iou ? 0 : chi2Quantile(m_params.gate_prob, 2);
	Eigen::MatrixXd c = Eigen::MatrixXd::Constant(long(m_tracks.size()), long(boxes.size()), kInf);
	for (size_t i = 0; i < m_tracks.size(); ++i)
	{
		const TBoxTrack& t = m_tracks[i];
		for (size_t j = 0; j < boxes.size(); ++j)
		{
			const TWorldBox& b = boxes[j];
			if (b.cls != t.cls) continue;
			if (iou)
			{
				const double v = models::bevIoU(footprint(t.x.head<3>(), t.x.segment<2>(3)),
				                                footprint(b.pose, b.extent));
				if (v >= m_params.min_iou) c(long(i), long(j)) = 1 - v;
				continue;
			}
			const Eigen::Matrix2d S =
			    t.P.topLeftCorner<2, 2>() + boxNoise(m_params, b).topLeftCorner<2, 2>();
			const Eigen::Vector2d d = b.pose.head<2>() - t.x.head<2>();
			const double d2 = d.dot(S.llt().solve(d));
			if (d2 <= gate) c(long(i), long(j)) = d2;
		}
	}
	return c;
}

void CBoxTracker::updateTrack(TBoxTrack& t, const TWorldBox& box, bool flip) const
{
	Vector5d z;
	z << box.pose.head<2>(), box.pose.z() + (flip ? M_PI : 0.0), box.extent;
	Vector5d r = z - t.x.head<5>();
	r(2) = models::wrapToPi(r(2));
	const Matrix5d S = t.P.topLeftCorner<5, 5>() + boxNoise(m_params, box);
	// K = P H' S^-1 with H = [I5 0]
	const Eigen::Matrix<double, 7, 5> K = S.llt().solve(t.P.leftCols<5>().transpose()).transpose();
	t.x += K * r;
	t.x(2) = models::wrapToPi(t.x(2));
	Matrix7d IKH = Matrix7d::Identity();
	IKH.leftCols<5>() -= K;
	t.P = IKH * t.P * IKH.transpose() + K * boxNoise(m_params, box) * K.transpose();  // Joseph
	t.P = (0.5 * (t.P + t.P.transpose())).eval();
}

bool CBoxTracker::manage(TBoxTrack& t, bool hit, TBoxAssignment& out) const
{
	++t.age;
	t.updated = hit;
	if (hit)
	{
		++t.hits;
		t.misses = 0;
		if (t.state == ETrackState::Lost) t.state = ETrackState::Confirmed;
	}
	else
	{
		++t.misses;
		if (t.state == ETrackState::Confirmed) t.state = ETrackState::Lost;
	}
	if (t.state == ETrackState::Tentative)
	{
		if (t.hits >= m_params.min_hits)
		{
			t.state = ETrackState::Confirmed;
			++out.confirmations;
		}
		// the frames left in the window after this one cannot give the missing hits
		else if (t.hits + (m_params.birth_window - 1 - t.age) < m_params.min_hits)
			return true;
	}
	return t.misses >= m_params.max_age;
}

TBoxAssignment CBoxTracker::update(const std::vector<TWorldBox>& boxes)
{
	for (size_t j = 0; j < boxes.size(); ++j) checkBox(boxes[j], j);
	TBoxAssignment out;
	out.track.assign(boxes.size(), -1);
	out.flipped.assign(boxes.size(), false);
	const std::vector<int> col = models::solveAssignment(costs(boxes));
	std::vector<TBoxTrack> kept;
	kept.reserve(m_tracks.size() + boxes.size());
	for (size_t i = 0; i < m_tracks.size(); ++i)
	{
		TBoxTrack& t = m_tracks[i];
		const int j = col[i];
		if (j >= 0)
		{
			const TWorldBox& b = boxes[size_t(j)];
			const bool flip = std::abs(models::wrapToPi(b.pose.z() - t.x(2))) > M_PI / 2;
			updateTrack(t, b, flip);
			t.score = b.score;
			out.track[size_t(j)] = t.id;
			out.flipped[size_t(j)] = flip;
		}
		if (manage(t, j >= 0, out))
			++out.deletions;
		else
			kept.push_back(t);
	}
	for (size_t j = 0; j < boxes.size(); ++j)
	{
		const TWorldBox& b = boxes[j];
		if (out.track[j] >= 0 || !(b.score >= m_params.min_score)) continue;
		TBoxTrack t;
		t.id = m_nextId++;
		t.cls = b.cls;
		t.x << b.pose.head<2>(), models::wrapToPi(b.pose.z()), b.extent, 0, 0;
		t.P.topLeftCorner<5, 5>() = boxNoise(m_params, b);
		t.P(5, 5) = t.P(6, 6) = m_params.velocity_std * m_params.velocity_std;
		t.hits = 1;
		t.updated = true;
		t.score = b.score;
		++out.births;
		if (t.hits >= m_params.min_hits)
		{
			t.state = ETrackState::Confirmed;
			++out.confirmations;
		}
		out.track[j] = t.id;
		kept.push_back(t);
	}
	m_tracks = std::move(kept);
	return out;
}
}  // namespace dynslam::estimator
