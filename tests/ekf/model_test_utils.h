#pragma once
/** Helpers of the object-model tests (test_object_model_ca.cpp, test_multiple_model.cpp): central
 * differences with wrapped angle outputs, and the message of an exception. */
#include <dynslam/core/models/se2.h>

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace dynslam_test
{
/** Central differences of f at x (step h); output rows in `angles` wrapped. */
inline Eigen::MatrixXd numericJ(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                const Eigen::VectorXd& x, const std::vector<int>& angles,
                                double h = 1e-6)
{
	const Eigen::VectorXd f0 = f(x);
	Eigen::MatrixXd J(f0.size(), x.size());
	for (Eigen::Index j = 0; j < x.size(); ++j)
	{
		Eigen::VectorXd p = x, m = x;
		p[j] += h;
		m[j] -= h;
		Eigen::VectorXd d = f(p) - f(m);
		for (const int a : angles) d[a] = dynslam::models::wrapToPi(d[a]);
		J.col(j) = d / (2 * h);
	}
	return J;
}

/** The message of the std::exception f throws ("" if none). */
inline std::string errorOf(const std::function<void()>& f)
{
	try
	{
		f();
	}
	catch (const std::exception& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace dynslam_test
