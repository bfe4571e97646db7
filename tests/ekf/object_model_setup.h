#pragma once
/** The filter setup of the object-model tests (test_object_model_ctrv.cpp,
 * test_object_model_bad_input.cpp): Cartesian readings with the tiny scenario's noise, the
 * ego start known exactly, near-rigid objects, and the cv / ctrv keys used by both; and the
 * minimal INI of the object-model option tests (loadCartesianFilter, expectScalarCvKey). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

#include "tiny_scenario.h"

namespace dynslam_test
{
inline void configureObjectModel(dynslam::CDynamicKFSLAM2D& f, const TinyScenarioOptions& o,
                                 const std::string& model)
{
	f.options.measurement_model = dynslam::models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0.setZero();
	f.options.Sigma_xi = Eigen::Matrix2d::Identity() * 1e-6;
	f.options.object_model = model;
	f.options.cv.dt = 1.0;
	f.options.cv.accel_psd = Eigen::Vector3d(1e-4, 1e-4, 1e-6);
	f.options.cv.velocity_prior_std = Eigen::Vector3d(0.1, 0.1, 0.05);
	f.reset();
}

/** A filter loaded from `[DynamicKFSLAM]` with the Cartesian model, Sigma_v = [1e-4 1e-4] and
 * the keys in `extra` (one "key = value\n" per key). */
inline std::unique_ptr<dynslam::CDynamicKFSLAM2D> loadCartesianFilter(const std::string& extra)
{
	mrpt::config::CConfigFileMemory ini;
	ini.setContent(
	    std::string("[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1e-4 1e-4]\n") +
	    extra);
	auto f = std::make_unique<dynslam::CDynamicKFSLAM2D>();
	f->loadOptions(ini);
	return f;
}

/** The cv keys every cv option test starts from. */
inline const std::string kCvKeys = "object_model = cv\n[ObjectModel]\ncv_dt = 0.5\n";
/** The checks of a scalar cv key that is off (0) by default: read from the INI as `text`
 * (= value), negative values rejected at load, infinite and NaN values by validate(), and
 * dumped aligned as "key<spaces>= text". */
inline void expectScalarCvKey(double dynslam::estimator::TCvParams::*member, const std::string& key,
                              double value, const std::string& text)
{
	const auto load = [&](const std::string& extra)
	{ return loadCartesianFilter(kCvKeys + extra)->options.cv.*member; };
	EXPECT_EQ(load(""), 0.0) << key << ": off by default";
	EXPECT_EQ(load(key + " = " + text + "\n"), value) << key;
	EXPECT_THROW(load(key + " = -1\n"), std::invalid_argument) << key;
	dynslam::estimator::TCvParams p;
	p.*member = std::numeric_limits<double>::infinity();
	EXPECT_THROW(p.validate(), std::invalid_argument) << key;
	p.*member = std::nan("");
	EXPECT_THROW(p.validate(), std::invalid_argument) << key;
	dynslam::CDynamicKFSLAM2D f;
	f.options.cv.*member = value;
	std::ostringstream dump;
	f.options.dumpToTextStream(dump);
	const std::string line = key + std::string(31 - key.size(), ' ') + "= " + text;
	EXPECT_NE(dump.str().find(line), std::string::npos) << line;
}
}  // namespace dynslam_test
