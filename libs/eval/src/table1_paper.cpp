/** @file table1_paper.cpp
 * Table I of Chiu (arXiv 2207.05043) as printed (copied cell by cell from
 * /work/shared/seed/table1.csv, which was read from the paper's text). kNA = "N/A".
 * Garbled cells are kept as printed and listed in paperTable1GarbledCells(). */
#include "table1_paper.h"

#include <limits>

namespace dynslam::eval::detail
{
namespace
{
constexpr double kNA = std::numeric_limits<double>::quiet_NaN();
}

// noise_level, quantity, ego_poses, static_features, agent1..3_features, agent1..3_poses
const std::vector<TPaperRow>& paperTable1Rows()
{
	static const std::vector<TPaperRow> rows = {
	    {"w1v1", "x_m", {0.008, 0.014, 0.014, 0.014, 0.014, 0.001, 0.001, 0.001}},
	    {"w1v1", "y_m", {0.032, 0.028, 0.003, 0.001, 0.025, 0.028, 0.035, 0.006}},
	    {"w1v1", "theta_rad", {0.000, kNA, kNA, kNA, kNA, 0.001, 0.001, 0.006}},
	    {"w1v2", "x_m", {0.035, 0.062, 0.062, 0.062, 0.063, 0.002, 0.002, 0.002}},
	    {"w1v2", "y_m", {0.061, 0.059, 0.007, 0.003, 0.052, 0.054, 0.066, 0.012}},
	    {"w1v2", "theta_rad", {0.000, kNA, kNA, kNA, kNA, 0.004, 0.004, 0.015}},
	    {"w1v3", "x_m", {0.089, 0.155, 0.157, 0.157, 0.156, 0.005, 0.004, 0.006}},
	    {"w1v3", "y_m", {0.152, 0.157, 0.168, 0.009, 0.138, 0.137, 0.166, 0.032}},
	    {"w1v3", "theta_rad", {0.000, kNA, kNA, kNA, kNA, 0.011, 0.011, 0.054}},
	    {"w2v1", "x_m", {0.008, 0.012, 0.012, 0.012, 0.012, 0.002, 0.002, 0.003}},
	    {"w2v1", "y_m", {0.072, 0.053, 0.004, 0.004, 0.046, 0.065, 0.080, 0.014}},
	    {"w2v1", "theta_rad", {0.000, kNA, kNA, kNA, kNA, 0.001, 0.001, 0.005}},
	    {"w2v2", "x_m", {0.028, 0.048, 0.049, 0.048, 0.050, 0.003, 0.003, 0.004}},
	    {"w2v2", "y_m", {0.088, 0.0074, 0.007, 0.005, 0.065, 0.078, 0.004, 0.018}},
	    {"w2v2", "theta_rad", {0.000, kNA, kNA, kNA, kNA, 0.004, 0.004, 0.016}},
	    {"w2v3", "x_m", {0.103, 0.181, 0.182, 0.182, 0.182, 0.005, 0.005, 0.007}},
	    {"w2v3", "y_m", {0.200, 0.196, 0.020, 0.010, 0.173, 0.180, 0.217, 0.041}},
	    {"w2v3", "theta_rad", {0.000, kNA, kNA, kNA, kNA, 0.012, 0.012, 0.053}},
	    {"w3v1", "x_m", {0.017, 0.017, 0.019, 0.016, 0.021, 0.009, 0.008, 0.012}},
	    {"w3v1", "y_m", {0.287, 0.232, 0.016, 0.012, 0.202, 0.259, 0.317, 0.058}},
	    {"w3v1", "theta_rad", {0.001, kNA, kNA, kNA, kNA, 0.001, 0.001, 0.005}},
	    {"w3v2", "x_m", {0.029, 0.043, 0.044, 0.044, 0.045, 0.010, 0.009, 0.013}},
	    {"w3v2", "y_m", {0.226, 0.164, 0.015, 0.009, 0.144, 0.200, 0.246, 0.044}},
	    {"w3v2", "theta_rad", {0.001, kNA, kNA, kNA, kNA, 0.004, 0.004, 0.016}},
	    {"w3v3", "x_m", {0.093, 0.161, 0.161, 0.010, 0.014, 0.010, 0.010, 0.014}},
	    {"w3v3", "y_m", {0.312, 0.264, 0.027, 0.014, 0.233, 0.277, 0.340, 0.061}},
	    {"w3v3", "theta_rad", {0.001, kNA, kNA, kNA, kNA, 0.012, 0.013, 0.053}},
	};
	return rows;
}

const std::vector<TPaperGarbled>& paperTable1GarbledCells()
{
	static const std::vector<TPaperGarbled> cells = {
	    {"w2v2", "y_m", "static_features", "0.0074 is probably 0.074"},
	    {"w2v2", "y_m", "agent2_poses", "0.004: the neighbouring levels suggest about 0.09"},
	    {"w3v3", "x_m", "agent2_features", "0.010: the other feature columns are about 0.16"},
	    {"w3v3", "x_m", "agent3_features", "0.014: the other feature columns are about 0.16"},
	};
	return cells;
}
}  // namespace dynslam::eval::detail
