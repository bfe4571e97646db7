/** `@include` in INI files (libs/common/config_include.h, doc/configuration.md): relative
 * paths, later keys override included ones, MRPT's own @define still works across an include,
 * and every bad include is a clear error naming the file. */
#include <dynslam/common/config_include.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using dynslam::config::loadIniWithIncludes;
using dynslam::config::readIniText;

namespace
{
/** A fresh directory under the system temp dir for one test. */
struct TTempDir
{
	fs::path dir;
	explicit TTempDir(const std::string& name)
	{
		dir = fs::temp_directory_path() / ("dynslam_config_include_" + name);
		fs::remove_all(dir);
		fs::create_directories(dir / "profiles");
	}
	~TTempDir() { fs::remove_all(dir); }
	std::string write(const std::string& rel, const std::string& text) const
	{
		const fs::path p = dir / rel;
		std::ofstream(p) << text;
		return p.string();
	}
};

/** The message of the std::runtime_error thrown by f ("" if none). */
template <class F>
std::string errorOf(F f)
{
	try
	{
		f();
	}
	catch (const std::runtime_error& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(ConfigInclude, RelativeIncludeAndLaterKeysOverride)
{
	TTempDir t("override");
	t.write("profiles/base.ini",
	        "@define NOISE 0.25\n[ObjectModel]\ncv_gate = 0.5\n[DynamicKFSLAM]\nobject_model = cv\n"
	        "[Other]\nx = 1\n");
	t.write("profiles/mid.ini", "@include base.ini  # a comment\n[ObjectModel]\ncv_gate = 0.9\n");
	const std::string app =
	    t.write("app.ini",
	            "; a comment\n@include profiles/mid.ini\n\n[ObjectModel]\ncv_gate = 0.999\n"
	            "[DynamicKFSLAM]\nSigma_v = [${NOISE} 1]\n");
	mrpt::config::CConfigFileMemory c;
	std::vector<std::string> files;
	loadIniWithIncludes(app, c, &files);
	ASSERT_EQ(files.size(), 3u);
	EXPECT_EQ(files[0], app);
	EXPECT_EQ(c.read_string("ObjectModel", "cv_gate", ""), "0.999");      // the app's, last
	EXPECT_EQ(c.read_string("DynamicKFSLAM", "object_model", ""), "cv");  // from base.ini
	EXPECT_EQ(c.read_string("Other", "x", ""), "1");
	EXPECT_EQ(c.read_string("DynamicKFSLAM", "Sigma_v", ""), "[0.25 1]");  // @define of base
	// Without the app's own value the nearer include wins over the farther one.
	const std::string app2 = t.write("app2.ini", "@include profiles/mid.ini\n");
	loadIniWithIncludes(app2, c);
	EXPECT_EQ(c.read_string("ObjectModel", "cv_gate", ""), "0.9");
}

TEST(ConfigInclude, MissingFileNamesTheIncludingFileAndLine)
{
	TTempDir t("absent_file");
	const std::string app = t.write("app.ini", "; x\n@include profiles/nope.ini\n[A]\nk = 1\n");
	const std::string e = errorOf([&] { readIniText(app); });
	EXPECT_NE(e.find(app), std::string::npos) << e;
	EXPECT_NE(e.find("line 2"), std::string::npos) << e;
	EXPECT_NE(e.find("nope.ini"), std::string::npos) << e;
	EXPECT_NE(e.find("not found"), std::string::npos) << e;
	const std::string top = (t.dir / "absent.ini").string();
	EXPECT_NE(errorOf([&] { readIniText(top); }).find(top), std::string::npos);
}

TEST(ConfigInclude, CircularIncludeIsAnErrorWithTheChain)
{
	TTempDir t("cycle");
	t.write("profiles/a.ini", "@include b.ini\n[A]\nk = 1\n");
	t.write("profiles/b.ini", "@include a.ini\n[B]\nk = 2\n");
	const std::string app = t.write("app.ini", "@include profiles/a.ini\n");
	const std::string e = errorOf([&] { readIniText(app); });
	EXPECT_NE(e.find("circular @include"), std::string::npos) << e;
	EXPECT_NE(e.find("b.ini"), std::string::npos) << e;
	EXPECT_NE(e.find("a.ini -> "), std::string::npos) << e;
	// A file including itself.
	const std::string self = t.write("self.ini", "@include self.ini\n");
	EXPECT_NE(errorOf([&] { readIniText(self); }).find("circular @include"), std::string::npos);
	// The same file included twice side by side is not circular.
	t.write("profiles/c.ini", "[C]\nk = 3\n");
	const std::string twice =
	    t.write("twice.ini", "@include profiles/c.ini\n@include profiles/c.ini\n");
	EXPECT_EQ(errorOf([&] { readIniText(twice); }), "");
}

TEST(ConfigInclude, DepthLimitBothSidesOfTheBoundary)
{
	TTempDir t("nesting");
	// chain_0 includes chain_1 ... chain_n-1 includes leaf: n nested includes below chain_0.
	const auto chain = [&](int n)
	{
		t.write("profiles/leaf.ini", "[L]\nk = 1\n");
		for (int i = 0; i < n; ++i)
			t.write("profiles/chain_" + std::to_string(i) + ".ini",
			        "@include " +
			            (i + 1 < n ? "chain_" + std::to_string(i + 1) + ".ini" : "leaf.ini") +
			            "\n");
		return (t.dir / "profiles" / "chain_0.ini").string();
	};
	// chain_0 is the top file; it reaches leaf.ini through n nested includes.
	const int k = dynslam::config::kMaxIncludeDepth;
	EXPECT_EQ(errorOf([&] { readIniText(chain(k)); }), "");
	const std::string e = errorOf([&] { readIniText(chain(k + 1)); });
	EXPECT_NE(e.find("nested deeper than " + std::to_string(k)), std::string::npos) << e;
	EXPECT_NE(e.find("chain_"), std::string::npos) << e;
}

TEST(ConfigInclude, MisplacedIncludesAndKeysAreErrors)
{
	TTempDir t("placement");
	t.write("profiles/p.ini", "[A]\nk = 1\n");
	const std::string after = t.write("after.ini", "[A]\nk = 2\n@include profiles/p.ini\n");
	std::string e = errorOf([&] { readIniText(after); });
	EXPECT_NE(e.find("line 3"), std::string::npos) << e;
	EXPECT_NE(e.find("after a section header"), std::string::npos) << e;
	const std::string noName = t.write("noname.ini", "@include   \n[A]\n");
	EXPECT_NE(errorOf([&] { readIniText(noName); }).find("without a file name"), std::string::npos);
	const std::string stray = t.write("stray.ini", "@include profiles/p.ini\nk = 3\n[A]\n");
	e = errorOf([&] { readIniText(stray); });
	EXPECT_NE(e.find("line 2"), std::string::npos) << e;
	EXPECT_NE(e.find("before the first section header"), std::string::npos) << e;
	// A file without includes may still hold keys before its first section (MRPT's "" section).
	const std::string plain = t.write("plain.ini", "k = 3\n[A]\nk = 4\n");
	EXPECT_EQ(errorOf([&] { readIniText(plain); }), "");
	// "@included" is not the directive.
	const std::string word = t.write("word.ini", "[A]\n@included = 1\n");
	EXPECT_EQ(errorOf([&] { readIniText(word); }), "");
}

TEST(ConfigInclude, ProfileOverlayCarriesTheModuleSections)
{
	// dynslam-compare's row `default` (CCompareApp::paramsFor): the profile's keys of
	// [DynamicKFSLAM] and of the module sections replace the app's; the app's other keys stay.
	TTempDir t("overlay");
	const std::string profile =
	    t.write("profiles/p.ini",
	            "[DynamicKFSLAM]\nprior_gauge = anchor\n[ObjectModel]\ncv_gate = 0.5\n"
	            "[Classify]\nclassify_alpha = 0.02\n[Elsewhere]\nx = 2\n");
	mrpt::config::CConfigFileMemory base(
	    "[DynamicKFSLAM]\nSigma_v = [1 1]\nprior_gauge = prior\n[ObjectModel]\ncv_dt = 0.1\n"
	    "cv_gate = 0.9\n[Elsewhere]\nx = 1\n");
	mrpt::config::CConfigFileMemory out;
	const std::vector<std::string> written = dynslam::config::overlayProfile(
	    base, profile, {"DynamicKFSLAM", "ObjectModel", "OdometryBias", "Classify"}, out);
	EXPECT_EQ(written,
	          (std::vector<std::string>{"[DynamicKFSLAM] prior_gauge", "[ObjectModel] cv_gate",
	                                    "[Classify] classify_alpha"}));
	EXPECT_EQ(out.read_string("DynamicKFSLAM", "prior_gauge", ""), "anchor");
	EXPECT_EQ(out.read_string("DynamicKFSLAM", "Sigma_v", ""), "[1 1]");
	EXPECT_EQ(out.read_string("ObjectModel", "cv_gate", ""), "0.5");
	EXPECT_EQ(out.read_string("ObjectModel", "cv_dt", ""), "0.1");
	EXPECT_EQ(out.read_string("Classify", "classify_alpha", ""), "0.02");
	EXPECT_EQ(out.read_string("Elsewhere", "x", ""), "1");  // not a section of the overlay
	// A profile without the first section is not a profile of it.
	const std::string none = t.write("profiles/none.ini", "[ObjectModel]\ncv_gate = 0.5\n");
	const std::string e = errorOf(
	    [&] {
		    dynslam::config::overlayProfile(base, none, {"DynamicKFSLAM", "ObjectModel"}, out);
	    });
	EXPECT_NE(e.find("no section [DynamicKFSLAM]"), std::string::npos) << e;
}
