#pragma once
/** @file table1.h
 * Table I of Chiu (arXiv 2207.05043): root-mean-squared errors per noise level (rows: level x
 * quantity x / y / theta; columns: ego poses, static features, agent 1-3 features, agent 1-3
 * poses), averaged over Monte Carlo runs, with the paper's published numbers beside ours.
 *
 * Agent k is the k-th object of the ground truth (TRunMetrics::objects[k-1], i.e. in
 * io::TGroundTruth::objects order); objects beyond the third are not in the table. */
#include <dynslam/eval/metrics.h>

#include <array>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace dynslam::eval
{
constexpr int kTable1Columns = 8;
constexpr int kTable1Quantities = 3;  ///< x (m), y (m), theta (rad)
constexpr int kTable1Agents = 3;

/** Column names as in table1.csv: ego_poses, static_features, agent1_features, ...,
 * agent3_poses. */
const std::array<std::string, kTable1Columns>& table1ColumnNames();
/** Quantity names as in table1.csv: x_m, y_m, theta_rad. */
const std::array<std::string, kTable1Quantities>& table1QuantityNames();
/** The paper's noise level labels, w1v1, w1v2, ..., w3v3 (Sigma_w,i with Sigma_v,j). */
const std::vector<std::string>& paperNoiseLevels();

using TTable1Values = std::array<std::array<double, kTable1Columns>, kTable1Quantities>;

/** One run's Table I cells ([quantity][column]; NaN where N/A or not estimated). Feature
 * columns have no theta. */
TTable1Values table1Values(const TRunMetrics& m);

/** One cell averaged over runs: mean and sample standard deviation of the finite per-run
 * values; runs = how many runs had a finite value. */
struct TTable1Cell
{
	double mean = kNaN;
	double std = kNaN;
	int runs = 0;
};

struct TTable1Level
{
	std::string label;  ///< e.g. "w2v3"
	int runs = 0;       ///< runs aggregated
	std::array<std::array<TTable1Cell, kTable1Columns>, kTable1Quantities> cells;
};

struct TTable1
{
	std::vector<TTable1Level> levels;
};

/** Averages the runs of one noise level (the paper: "averaged over 25 experiments"). */
TTable1Level aggregateTable1Level(const std::string& label, const std::vector<TRunMetrics>& runs);

/** The paper's published cell (nullopt: N/A, or a level the paper does not have). */
std::optional<double> paperTable1Value(const std::string& level, int quantity, int column);
/** True for the cells that look like extraction errors in the source text (kept as printed):
 * w2v2 y static features 0.0074 (probably 0.074), w2v2 y agent 2 poses 0.004 (neighbours
 * ~0.09), w3v3 x agent 2 and 3 features 0.010, 0.014 (other features ~0.16). */
bool paperTable1Garbled(const std::string& level, int quantity, int column);

/** A cell where ours and the paper's differ by more than a factor. */
struct TTable1Deviation
{
	std::string level;
	int quantity = 0, column = 0;
	double ours = kNaN, paper = kNaN;
	double ratio = kNaN;  ///< ours / paper (inf if the paper prints 0.000)
	bool paper_garbled = false;
};

/** Cells where ours > factor x paper (both finite). A paper value printed as 0.000 means
 * < 0.0005: ours counts as worse only if ours >= factor x 0.0005. */
std::vector<TTable1Deviation> worseThanPaper(const TTable1& table, double factor = 3.0);

/** Markdown in the paper's layout; each cell "ours / paper", garbled paper cells marked with a
 * dagger and explained below the table, then the list of worseThanPaper(table, 3) cells. */
void writeTable1Markdown(std::ostream& os, const TTable1& table);
/** CSV, one row per noise level and quantity:
 * noise_level,quantity,runs,<col>_ours,<col>_ours_std,<col>_paper,... for the 8 columns, then
 * paper_garbled (';'-separated names of garbled paper columns in that row). Empty = N/A. */
void writeTable1Csv(std::ostream& os, const TTable1& table);

/** Formats a Table I number: 3 decimals like the paper, or 2 significant digits in scientific
 * notation below 0.001 (so small errors do not print as 0.000); "N/A" for NaN. */
std::string formatTable1Number(double v);
}  // namespace dynslam::eval
