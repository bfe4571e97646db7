#include <dynslam/eval/chi2.h>

#include <stdexcept>
#include <string>

namespace dynslam::eval
{
TChi2Interval averageChi2Bounds(double total_dof, int runs, double confidence)
{
	if (runs < 1)
		throw std::invalid_argument("averageChi2Bounds: runs must be >= 1, got " +
		                            std::to_string(runs));
	const TChi2Interval s = chi2Interval(total_dof, confidence);
	return {s.lower / runs, s.upper / runs};
}
}  // namespace dynslam::eval
