#include <dynslam/eval/covariance_writer.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace dynslam::eval
{
namespace
{
std::string full(double v)
{
	char b[40];
	std::snprintf(b, sizeof(b), "%.17g", v);
	return b;
}

void matrix(std::ostream& os, const Eigen::MatrixXd& m)
{
	for (Eigen::Index r = 0; r < m.rows(); ++r)
		for (Eigen::Index c = 0; c < m.cols(); ++c) os << ' ' << full(m(r, c));
	os << '\n';
}
}  // namespace

void writeCovariances(std::ostream& os, const TRunEstimates& est)
{
	os << "# dynslam covariance file, version 1 (format: libs/eval/include/dynslam/eval/"
	      "covariance_writer.h, doc/apps.md)\n"
	      "# ego STEP T c00..c22 (x y theta, row-major) | landmark ID c00..c11 | "
	      "landmarks_joint_ids N IDs | landmarks_joint_row I values | object_feature OBJECT "
	      "FEATURE c00..c11 | object_pose OBJECT STEP DIM values\n";
	std::vector<const TEgoEstimate*> ego;
	for (const auto& e : est.ego) ego.push_back(&e);
	std::sort(ego.begin(), ego.end(), [](auto a, auto b) { return a->step < b->step; });
	for (const auto* e : ego)
	{
		os << "ego " << e->step << ' ' << full(e->t);
		matrix(os, e->cov);
	}
	std::vector<size_t> order(est.landmarks.size());
	for (size_t i = 0; i < order.size(); ++i) order[i] = i;
	std::sort(order.begin(), order.end(),
	          [&](size_t a, size_t b) { return est.landmarks[a].id < est.landmarks[b].id; });
	for (size_t i : order)
	{
		os << "landmark " << est.landmarks[i].id;
		matrix(os, est.landmarks[i].cov);
	}
	const Eigen::Index n2 = Eigen::Index(2 * est.landmarks.size());
	if (n2 > 0 && est.landmarks_cov.rows() == n2 && est.landmarks_cov.cols() == n2)
	{
		os << "landmarks_joint_ids " << est.landmarks.size();
		for (const auto& l : est.landmarks) os << ' ' << l.id;
		os << '\n';
		for (Eigen::Index r = 0; r < n2; ++r)
		{
			os << "landmarks_joint_row " << r;
			matrix(os, est.landmarks_cov.row(r));
		}
	}
	for (const auto& f : est.object_features)
	{
		os << "object_feature " << f.object << ' ' << f.feature;
		matrix(os, f.cov);
	}
	for (const auto& p : est.object_poses)
	{
		os << "object_pose " << p.object << ' ' << p.step << ' ' << p.cov.rows();
		matrix(os, p.cov);
	}
}
}  // namespace dynslam::eval
