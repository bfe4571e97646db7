// Table I: per-run values, aggregation over runs, paper data, Markdown and CSV writers.
#include <dynslam/eval/table1.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace dynslam::eval;

namespace
{
TRunMetrics fakeRun(double scale)
{
	TRunMetrics m;
	m.ego.x = 0.010 * scale;
	m.ego.y = 0.020 * scale;
	m.ego.theta = 0.0005 * scale;
	m.static_map.x = 0.030 * scale;
	m.static_map.y = 0.040 * scale;
	for (int k = 0; k < 3; ++k)
	{
		TObjectMetrics o;
		o.object = k;
		o.features.x = 0.1 * (k + 1) * scale;
		o.features.y = 0.2 * (k + 1) * scale;
		o.poses.x = 0.01 * (k + 1) * scale;
		o.poses.y = 0.02 * (k + 1) * scale;
		o.poses.theta = k == 2 ? kNaN : 0.003 * scale;  // agent 3 translation-only here
		m.objects.push_back(o);
	}
	return m;
}
}  // namespace

TEST(Table1, PaperDataAsPrinted)
{
	EXPECT_EQ(paperNoiseLevels().size(), 9u);
	EXPECT_DOUBLE_EQ(*paperTable1Value("w1v1", 0, 0), 0.008);
	EXPECT_DOUBLE_EQ(*paperTable1Value("w3v3", 1, 7), 0.061);
	EXPECT_DOUBLE_EQ(*paperTable1Value("w2v2", 1, 1), 0.0074);
	EXPECT_FALSE(paperTable1Value("w1v1", 2, 1).has_value());  // N/A
	EXPECT_FALSE(paperTable1Value("w9v9", 0, 0).has_value());
	EXPECT_TRUE(paperTable1Garbled("w2v2", 1, 1));
	EXPECT_TRUE(paperTable1Garbled("w2v2", 1, 6));
	EXPECT_TRUE(paperTable1Garbled("w3v3", 0, 3));
	EXPECT_TRUE(paperTable1Garbled("w3v3", 0, 4));
	EXPECT_FALSE(paperTable1Garbled("w3v3", 0, 2));
	int n = 0;
	for (const auto& L : paperNoiseLevels())
		for (int q = 0; q < kTable1Quantities; ++q)
			for (int c = 0; c < kTable1Columns; ++c) n += paperTable1Value(L, q, c).has_value();
	EXPECT_EQ(n, 9 * (8 + 8 + 4));
}

TEST(Table1, AggregatesMeanOverRuns)
{
	const std::vector<TRunMetrics> runs = {fakeRun(1.0), fakeRun(3.0)};
	const TTable1Level L = aggregateTable1Level("w1v2", runs);
	EXPECT_EQ(L.runs, 2);
	EXPECT_NEAR(L.cells[0][0].mean, 0.020, 1e-12);  // ego x: (0.01 + 0.03) / 2
	EXPECT_NEAR(L.cells[0][0].std, std::sqrt(2.0) * 0.01, 1e-12);
	EXPECT_NEAR(L.cells[1][1].mean, 0.080, 1e-12);  // static y
	EXPECT_NEAR(L.cells[0][4].mean, 0.6, 1e-12);    // agent 3 features x
	EXPECT_NEAR(L.cells[2][5].mean, 0.006, 1e-12);  // agent 1 poses theta
	EXPECT_EQ(L.cells[2][7].runs, 0);               // agent 3 theta: NaN in every run
	EXPECT_TRUE(std::isnan(L.cells[2][1].mean));    // static theta: N/A
}

TEST(Table1, MarkdownPutsOursBesidePaper)
{
	TTable1 t;
	t.levels.push_back(aggregateTable1Level("w2v2", {fakeRun(1.0)}));
	std::ostringstream os;
	writeTable1Markdown(os, t);
	const std::string s = os.str();
	EXPECT_NE(s.find("| Noise level | Data | Ego Poses | Static Features |"), std::string::npos);
	EXPECT_NE(s.find("Σw,2, Σv,2 (w2v2), 1 runs | x (m) | 0.010 / 0.028 | 0.030 / 0.048 |"),
	          std::string::npos)
	    << s;
	// The garbled static y cell is marked and explained.
	EXPECT_NE(s.find("0.040 / 0.0074†"), std::string::npos) << s;
	EXPECT_NE(s.find("† Paper cell"), std::string::npos);
	// Small values are not printed as 0.000.
	EXPECT_NE(s.find("| θ (rad) | 5.0e-04 / 0.000 | N/A |"), std::string::npos) << s;
}

TEST(Table1, CsvOneRowPerLevelAndQuantity)
{
	TTable1 t;
	t.levels.push_back(aggregateTable1Level("w1v1", {fakeRun(1.0), fakeRun(1.0)}));
	t.levels.push_back(aggregateTable1Level("w3v3", {fakeRun(2.0)}));
	std::ostringstream os;
	writeTable1Csv(os, t);
	std::istringstream is(os.str());
	std::string line;
	std::vector<std::string> lines;
	while (std::getline(is, line)) lines.push_back(line);
	ASSERT_EQ(lines.size(), 1u + 2 * 3);
	EXPECT_EQ(lines[0].rfind("noise_level,quantity,runs,ego_poses_ours,ego_poses_ours_std,"
	                         "ego_poses_paper,static_features_ours",
	                         0),
	          0u);
	EXPECT_EQ(lines[1].rfind("w1v1,x_m,2,0.01,0,0.008,0.03,0,0.014,", 0), 0u) << lines[1];
	EXPECT_EQ(lines[3].rfind("w1v1,theta_rad,2,0.0005,0,0,,,,", 0), 0u) << lines[3];
	EXPECT_NE(lines[4].find(",agent2_features;agent3_features"), std::string::npos) << lines[4];
	// 3 + 8 * 3 + 1 fields per row.
	for (const auto& l : lines) EXPECT_EQ(std::count(l.begin(), l.end(), ','), 3 + 8 * 3) << l;
}

TEST(Table1, FormatsNumbers)
{
	EXPECT_EQ(formatTable1Number(0.0123), "0.012");
	EXPECT_EQ(formatTable1Number(0.00021), "2.1e-04");
	EXPECT_EQ(formatTable1Number(0.0), "0.000");
	EXPECT_EQ(formatTable1Number(kNaN), "N/A");
}

TEST(Table1, EmbeddedPaperDataEqualsTheSeedCsv)
{
	// tests/eval/data/table1_paper.csv is a verbatim copy of the paper's Table I as extracted
	// (the seed's table1.csv); every cell of the embedded data must match it.
	// (An absolute path: __FILE__ is relative under ccache's CCACHE_BASEDIR.)
	const auto path =
	    std::filesystem::path(DYNSLAM_TESTS_DIR) / "eval" / "data" / "table1_paper.csv";
	std::ifstream f(path);
	ASSERT_TRUE(f.good()) << path;
	std::string line;
	std::getline(f, line);
	int rows = 0, cells = 0;
	while (std::getline(f, line))
	{
		std::vector<std::string> v;
		std::stringstream ss(line);
		std::string c;
		while (std::getline(ss, c, ',')) v.push_back(c);
		while (v.size() < 10) v.push_back("");
		const auto& qn = table1QuantityNames();
		const int q = static_cast<int>(std::find(qn.begin(), qn.end(), v[1]) - qn.begin());
		ASSERT_LT(q, kTable1Quantities) << line;
		for (int col = 0; col < kTable1Columns; ++col)
		{
			const auto ours = paperTable1Value(v[0], q, col);
			if (v[2 + col].empty())
				EXPECT_FALSE(ours.has_value()) << line;
			else
			{
				ASSERT_TRUE(ours.has_value()) << line;
				EXPECT_DOUBLE_EQ(*ours, std::stod(v[2 + col])) << line;
				++cells;
			}
		}
		++rows;
	}
	EXPECT_EQ(rows, 27);
	EXPECT_EQ(cells, 9 * 20);
}

TEST(Table1, ListsCellsWorseThanThreeTimesThePaper)
{
	TTable1 t;
	// w1v1 paper: ego x 0.008, ego theta 0.000, agent 1 poses x 0.001.
	TRunMetrics m = fakeRun(1.0);
	m.ego.x = 0.025;                // 3.1x 0.008: listed
	m.ego.theta = 0.002;            // paper 0.000 means < 0.0005: 0.002 > 3 x 0.0005, listed
	m.objects[0].poses.x = 0.0029;  // 2.9x 0.001: not listed
	t.levels.push_back(aggregateTable1Level("w1v1", {m}));
	const auto w = worseThanPaper(t, 3.0);
	auto has = [&](int q, int c)
	{
		return std::any_of(w.begin(), w.end(),
		                   [&](const auto& d)
		                   { return d.level == "w1v1" && d.quantity == q && d.column == c; });
	};
	EXPECT_TRUE(has(0, 0));
	EXPECT_TRUE(has(2, 0));
	EXPECT_FALSE(has(0, 5));
	for (const auto& d : w)
	{
		if (d.quantity == 0 && d.column == 0)
		{
			EXPECT_NEAR(d.ratio, 0.025 / 0.008, 1e-12);
		}
	}
	// 0.0014 against a printed 0.000 is within 3 x 0.0005: not listed.
	t.levels[0].cells[2][0].mean = 0.0014;
	EXPECT_EQ(worseThanPaper(t, 3.0).size(), w.size() - 1);
	std::ostringstream os;
	writeTable1Markdown(os, t);
	EXPECT_NE(os.str().find("- w1v1 x_m ego_poses: 0.025 vs 0.008 (3.1x)"), std::string::npos)
	    << os.str();
}
