#include <dynslam/core/models/se2.h>
#include <dynslam/framework/variables.h>

#include <stdexcept>

namespace dynslam::framework
{
std::string toString(const TVarKey& k)
{
	const std::string t = std::to_string(k.step);
	switch (k.kind)
	{
		case VarKind::EgoPose:
			return "x[t " + t + "]";
		case VarKind::StaticLandmark:
			return "landmark " + std::to_string(k.id);
		case VarKind::ObjectFeature:
			return "f[obj " + std::to_string(k.id) + ", k " + std::to_string(k.feature) + ", t " +
			       t + "]";
		case VarKind::ObjectPose:
			return "xi[obj " + std::to_string(k.id) + ", t " + t + "]";
		case VarKind::ObjectBodyPose:
			return "O[obj " + std::to_string(k.id) + ", t " + t + "]";
		case VarKind::ObjectVelocity:
			return "v[obj " + std::to_string(k.id) + ", t " + t + "]";
	}
	return "?";
}

int angleIndex(VarKind kind, int dim)
{
	switch (kind)
	{
		case VarKind::EgoPose:
			return 2;
		case VarKind::ObjectPose:
		case VarKind::ObjectBodyPose:
			return dim == 3 ? 2 : -1;
		default:
			return -1;
	}
}

Eigen::VectorXd blockMinus(VarKind kind, const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
	if (a.size() != b.size()) throw std::invalid_argument("blockMinus: size mismatch");
	Eigen::VectorXd d = a - b;
	const int ai = angleIndex(kind, int(a.size()));
	if (ai >= 0) d[ai] = models::wrapToPi(d[ai]);
	return d;
}

Eigen::VectorXd blockPlus(VarKind kind, const Eigen::VectorXd& a, const Eigen::VectorXd& d)
{
	if (a.size() != d.size()) throw std::invalid_argument("blockPlus: size mismatch");
	Eigen::VectorXd s = a + d;
	const int ai = angleIndex(kind, int(a.size()));
	if (ai >= 0) s[ai] = models::wrapToPi(s[ai]);
	return s;
}
}  // namespace dynslam::framework
