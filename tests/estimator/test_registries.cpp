/** One registry per seam (estimator/seam_registries.h, ekf_registries.h): every name makes its
 * implementation, the capabilities agree with the instances, unknown names are clear errors. */
#include <dynslam/common/model_options.h>
#include <dynslam/ekf/ekf_registries.h>
#include <dynslam/estimator/seam_registries.h>
#include <gtest/gtest.h>

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
std::string errorOf(const std::function<void()>& f)
{
	try
	{
		f();
	}
	catch (const std::invalid_argument& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(Registries, ObjectMotionModelsAndTheirCapabilities)
{
	const auto& r = objectMotionModels();
	EXPECT_EQ(r.names(),
	          (std::vector<std::string>{"paper", "paper_smoothing", "cv", "ctrv", "ca", "mm"}));
	TObjectMotionParams p;
	for (const auto& name : r.names())
	{
		const auto m = r.make(name, p);
		EXPECT_EQ(m->objectCentric(), r.caps(name).object_centric) << name;
		TModelOptions o;
		o.object_model = name;
		EXPECT_EQ(o.objectCentric(), r.caps(name).object_centric) << name;
		// The capability the step asks instead of the name "none".
		EXPECT_EQ(m->actsOnNewPoses(), name != "paper") << name;
	}
	EXPECT_EQ(r.make("cv", p)->name(), "cv");
	EXPECT_EQ(r.make("ctrv", p)->name(), "ctrv");
	EXPECT_EQ(r.make("ca", p)->name(), "ca");
	EXPECT_EQ(r.make("ca", p)->velocityDim(3), 6);  // [v; a]
	EXPECT_FALSE(r.caps("ca").window);
	EXPECT_EQ(r.make("mm", p)->name(), "mm");
	EXPECT_EQ(r.make("mm", p)->modeCount(), 4);
	EXPECT_TRUE(r.caps("mm").framework);  // the EKF and Alg. 1
	EXPECT_FALSE(r.caps("mm").window);
	p.smoothing = true;  // paper with smoothing = true is the paper's smoothing
	EXPECT_EQ(r.make("paper", p)->name(), "paper_smoothing");
	EXPECT_TRUE(r.caps("paper_smoothing").smoothing);
	EXPECT_FALSE(r.caps("cv").window);
	const std::string e = errorOf([&] { r.make("ca_typo", p); });
	EXPECT_NE(e.find("object_model = ca_typo"), std::string::npos) << e;
	EXPECT_NE(e.find("ctrv"), std::string::npos) << e;
	TModelOptions bad;
	bad.object_model = "ca_typo";
	EXPECT_FALSE(bad.objectCentric());
	EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(Registries, UpdateEnginesRoutersAndLifecycles)
{
	const auto& e = ekfUpdateEngines();
	EXPECT_EQ(e.names(), (std::vector<std::string>{"gate", "none", "huber", "cauchy",
	                                               "gate_recovery", "jcbb"}));
	EXPECT_FALSE(updateEngines().has("jcbb"));  // MRPT's: registered by libs/ekf only
	TUpdateEngineParams p;
	p.gate_probability = 0.99;
	const std::vector<std::string> made{"sparse", "sparse",        "huber",
	                                    "cauchy", "gate_recovery", "jcbb"};
	for (size_t i = 0; i < made.size(); ++i)
		EXPECT_EQ(e.make(e.names()[i], p)->name(), made[i]) << e.names()[i];
	EXPECT_FALSE(e.caps("none").gate);
	EXPECT_TRUE(e.caps("gate").gate);
	EXPECT_TRUE(e.caps("jcbb").needs_gate);
	EXPECT_NE(errorOf([&] { e.make("huber2", p); }).find("outlier_method = huber2"),
	          std::string::npos);
	EXPECT_TRUE(routers().caps("classify").classifies);
	EXPECT_FALSE(routers().caps("ids").classifies);
	EXPECT_EQ(routers().make("classify", {})->name(), "classify");
	EXPECT_THROW(routers().make("bogus", {}), std::invalid_argument);
	const auto& l = stateLifecycles();
	EXPECT_EQ(l.make("full", {})->rewritesStorage(), l.caps("full").rewrites_storage);
	EXPECT_EQ(l.make("compressed", {})->rewritesStorage(), l.caps("compressed").rewrites_storage);
	EXPECT_THROW(l.make("compressed", {0, 8}), std::invalid_argument);
	// A name registers once.
	CUpdateEngineRegistry copy = e;
	EXPECT_THROW(
	    copy.add("gate",
	             [](const TUpdateEngineParams&) { return std::make_unique<CSparseUpdateEngine>(); },
	             {}),
	    std::logic_error);
}
