#include <dynslam/core/models/bev_box.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace dynslam::models
{
namespace
{
using Poly = std::vector<Eigen::Vector2d>;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
	return a.x() * b.y() - a.y() * b.x();
}

/** Keeps the part of `subject` on the left of the directed edge p -> q. */
Poly clipByEdge(const Poly& subject, const Eigen::Vector2d& p, const Eigen::Vector2d& q)
{
	Poly out;
	const Eigen::Vector2d e = q - p;
	for (size_t i = 0; i < subject.size(); ++i)
	{
		const Eigen::Vector2d& a = subject[i];
		const Eigen::Vector2d& b = subject[(i + 1) % subject.size()];
		const double da = cross(e, a - p), db = cross(e, b - p);
		if (da >= 0) out.push_back(a);
		if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
	}
	return out;
}

double area(const Poly& p)
{
	double s = 0;
	for (size_t i = 0; i < p.size(); ++i) s += cross(p[i], p[(i + 1) % p.size()]);
	return 0.5 * std::abs(s);
}

void checkBox(const TBevBox& b)
{
	if (!(std::isfinite(b.length) && std::isfinite(b.width) && b.length > 0 && b.width > 0) ||
	    !(std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.yaw)))
		throw std::invalid_argument("bevIoU: a box needs a finite pose and length, width > 0");
}
}  // namespace

Eigen::Matrix<double, 2, 4> bevCorners(const TBevBox& b)
{
	const double c = std::cos(b.yaw), s = std::sin(b.yaw);
	const double hl = b.length / 2, hw = b.width / 2;
	const double u[4] = {hl, -hl, -hl, hl}, v[4] = {hw, hw, -hw, -hw};
	Eigen::Matrix<double, 2, 4> k;
	for (int j = 0; j < 4; ++j) k.col(j) << b.x + c * u[j] - s * v[j], b.y + s * u[j] + c * v[j];
	return k;
}

double bevIntersectionArea(const TBevBox& a, const TBevBox& b)
{
	const auto ka = bevCorners(a), kb = bevCorners(b);
	Poly p;
	for (int j = 0; j < 4; ++j) p.push_back(ka.col(j));
	for (int j = 0; j < 4 && !p.empty(); ++j) p = clipByEdge(p, kb.col(j), kb.col((j + 1) % 4));
	return p.size() < 3 ? 0.0 : area(p);
}

double bevIoU(const TBevBox& a, const TBevBox& b)
{
	checkBox(a);
	checkBox(b);
	const double inter = bevIntersectionArea(a, b);
	const double uni = a.length * a.width + b.length * b.width - inter;
	return std::clamp(inter / uni, 0.0, 1.0);
}

double bevCentreDistance(const TBevBox& a, const TBevBox& b)
{
	return std::hypot(a.x - b.x, a.y - b.y);
}
}  // namespace dynslam::models
