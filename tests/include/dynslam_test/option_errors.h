#pragma once
/** Bad input of the model options: loading [DynamicKFSLAM] of `ini` must throw
 * std::invalid_argument whose message names every one of `words` (the key, its section, the
 * rule broken). Shared by the pruning, dropping and fusion tests (tests/framework,
 * tests/ekf). */
#include <dynslam/common/model_options.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace dynslam_test
{
inline void expectOptionsError(const std::string& ini, const std::vector<std::string>& words)
{
	mrpt::config::CConfigFileMemory c(ini);
	dynslam::TModelOptions o;
	try
	{
		o.loadFromConfigFile(c, "DynamicKFSLAM");
		ADD_FAILURE() << "no error for\n" << ini;
	}
	catch (const std::invalid_argument& e)
	{
		const std::string m = e.what();
		for (const auto& w : words) EXPECT_NE(m.find(w), std::string::npos) << w << " in " << m;
	}
}
}  // namespace dynslam_test
