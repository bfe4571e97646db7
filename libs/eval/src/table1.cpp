#include "dynslam/eval/table1.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "table1_paper.h"

namespace dynslam::eval
{
const std::array<std::string, kTable1Columns>& table1ColumnNames()
{
	static const std::array<std::string, kTable1Columns> names = {
	    "ego_poses",       "static_features", "agent1_features", "agent2_features",
	    "agent3_features", "agent1_poses",    "agent2_poses",    "agent3_poses"};
	return names;
}

const std::array<std::string, kTable1Quantities>& table1QuantityNames()
{
	static const std::array<std::string, kTable1Quantities> names = {"x_m", "y_m", "theta_rad"};
	return names;
}

const std::vector<std::string>& paperNoiseLevels()
{
	static const std::vector<std::string> levels = {"w1v1", "w1v2", "w1v3", "w2v1", "w2v2",
	                                                "w2v3", "w3v1", "w3v2", "w3v3"};
	return levels;
}

TTable1Values table1Values(const TRunMetrics& m)
{
	TTable1Values v;
	for (auto& q : v) q.fill(kNaN);
	auto put = [&](int col, const TRmse& r, bool withTheta)
	{
		v[0][col] = r.x;
		v[1][col] = r.y;
		if (withTheta) v[2][col] = r.theta;
	};
	put(0, m.ego, true);
	put(1, m.static_map, false);
	for (int k = 0; k < kTable1Agents && k < static_cast<int>(m.objects.size()); ++k)
	{
		put(2 + k, m.objects[k].features, false);
		put(5 + k, m.objects[k].poses, true);
	}
	return v;
}

TTable1Level aggregateTable1Level(const std::string& label, const std::vector<TRunMetrics>& runs)
{
	TTable1Level L;
	L.label = label;
	L.runs = static_cast<int>(runs.size());
	std::vector<TTable1Values> vals;
	for (const auto& r : runs) vals.push_back(table1Values(r));
	for (int q = 0; q < kTable1Quantities; ++q)
		for (int c = 0; c < kTable1Columns; ++c)
		{
			double s = 0, s2 = 0;
			int n = 0;
			for (const auto& v : vals)
				if (std::isfinite(v[q][c]))
				{
					s += v[q][c];
					++n;
				}
			TTable1Cell& cell = L.cells[q][c];
			cell.runs = n;
			if (n == 0) continue;
			cell.mean = s / n;
			for (const auto& v : vals)
				if (std::isfinite(v[q][c])) s2 += (v[q][c] - cell.mean) * (v[q][c] - cell.mean);
			cell.std = n > 1 ? std::sqrt(s2 / (n - 1)) : 0.0;
		}
	return L;
}

std::optional<double> paperTable1Value(const std::string& level, int quantity, int column)
{
	if (quantity < 0 || quantity >= kTable1Quantities || column < 0 || column >= kTable1Columns)
		return std::nullopt;
	for (const auto& r : detail::paperTable1Rows())
		if (level == r.level && table1QuantityNames()[quantity] == r.quantity)
		{
			const double v = r.values[column];
			if (std::isnan(v)) return std::nullopt;
			return v;
		}
	return std::nullopt;
}

bool paperTable1Garbled(const std::string& level, int quantity, int column)
{
	if (quantity < 0 || quantity >= kTable1Quantities || column < 0 || column >= kTable1Columns)
		return false;
	for (const auto& g : detail::paperTable1GarbledCells())
		if (level == g.level && table1QuantityNames()[quantity] == g.quantity &&
		    table1ColumnNames()[column] == g.column)
			return true;
	return false;
}

std::string formatTable1Number(double v)
{
	if (!std::isfinite(v)) return "N/A";
	char buf[32];
	if (v != 0 && std::abs(v) < 0.001)
		std::snprintf(buf, sizeof(buf), "%.1e", v);
	else
		std::snprintf(buf, sizeof(buf), "%.3f", v);
	return buf;
}

namespace
{
/// The paper prints its cells with as many decimals as given (0.0074 keeps 4).
std::string formatPaper(double v)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%.4f", v);
	std::string s = buf;
	while (s.size() > 5 && s.back() == '0') s.pop_back();  // keep at least 3 decimals
	return s;
}

std::string levelTitle(const std::string& label)
{
	// "wIvJ" -> "Σw,I, Σv,J (wIvJ)"
	const auto v = label.find('v');
	if (label.size() >= 4 && label[0] == 'w' && v != std::string::npos && v > 1 &&
	    v + 1 < label.size())
		return "Σw," + label.substr(1, v - 1) + ", Σv," + label.substr(v + 1) + " (" + label + ")";
	return label;
}

std::string csvNumber(double v)
{
	if (!std::isfinite(v)) return "";
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%.6g", v);
	return buf;
}
}  // namespace

std::vector<TTable1Deviation> worseThanPaper(const TTable1& table, double factor)
{
	std::vector<TTable1Deviation> out;
	for (const auto& L : table.levels)
		for (int q = 0; q < kTable1Quantities; ++q)
			for (int c = 0; c < kTable1Columns; ++c)
			{
				const auto paper = paperTable1Value(L.label, q, c);
				const double ours = L.cells[q][c].mean;
				if (!paper || !std::isfinite(ours)) continue;
				// The paper rounds to 3 decimals: 0.000 stands for anything below 0.0005.
				const double ref = std::max(*paper, 0.0005);
				if (ours <= factor * ref) continue;
				TTable1Deviation d;
				d.level = L.label;
				d.quantity = q;
				d.column = c;
				d.ours = ours;
				d.paper = *paper;
				d.ratio = *paper > 0 ? ours / *paper : std::numeric_limits<double>::infinity();
				d.paper_garbled = paperTable1Garbled(L.label, q, c);
				out.push_back(d);
			}
	return out;
}

void writeTable1Markdown(std::ostream& os, const TTable1& table)
{
	static const char* qTitle[kTable1Quantities] = {"x (m)", "y (m)", "θ (rad)"};
	os << "| Noise level | Data | Ego Poses | Static Features | Agent 1 Features | Agent 2 Features"
	      " | Agent 3 Features | Agent 1 Poses | Agent 2 Poses | Agent 3 Poses |\n";
	os << "|---|---|---|---|---|---|---|---|---|---|\n";
	bool anyGarbled = false;
	for (const auto& L : table.levels)
		for (int q = 0; q < kTable1Quantities; ++q)
		{
			os << "| "
			   << (q == 0 ? levelTitle(L.label) + ", " + std::to_string(L.runs) + " runs" : "")
			   << " | " << qTitle[q] << " |";
			for (int c = 0; c < kTable1Columns; ++c)
			{
				const auto paper = paperTable1Value(L.label, q, c);
				const TTable1Cell& cell = L.cells[q][c];
				if (!paper && cell.runs == 0)
				{
					os << " N/A |";
					continue;
				}
				os << " " << formatTable1Number(cell.mean) << " / ";
				if (paper)
				{
					os << formatPaper(*paper);
					if (paperTable1Garbled(L.label, q, c))
					{
						os << "†";
						anyGarbled = true;
					}
				}
				else
					os << "N/A";
				os << " |";
			}
			os << "\n";
		}
	os << "\nEach cell: ours / paper. Ours: mean over the runs of each run's RMSE "
	      "(doc/metrics.md); paper: Table I of Chiu, arXiv 2207.05043 (25 runs per level). "
	      "N/A: not defined (no heading for points) or not in the paper.\n";
	if (anyGarbled)
	{
		os << "\n† Paper cell that looks like a text-extraction error, kept as printed:\n";
		for (const auto& g : detail::paperTable1GarbledCells())
			os << "- " << g.level << " " << g.quantity << " " << g.column << ": " << g.note << "\n";
	}
	const auto worse = worseThanPaper(table, 3.0);
	if (!worse.empty())
	{
		os << "\nCells where ours is more than 3x the paper's:\n";
		for (const auto& d : worse)
		{
			char ratio[32] = "paper prints 0.000";
			if (std::isfinite(d.ratio)) std::snprintf(ratio, sizeof(ratio), "%.1fx", d.ratio);
			os << "- " << d.level << " " << table1QuantityNames()[d.quantity] << " "
			   << table1ColumnNames()[d.column] << ": " << formatTable1Number(d.ours) << " vs "
			   << formatPaper(d.paper) << " (" << ratio << ")"
			   << (d.paper_garbled ? ", paper cell garbled" : "") << "\n";
		}
	}
}

void writeTable1Csv(std::ostream& os, const TTable1& table)
{
	os << "noise_level,quantity,runs";
	for (const auto& c : table1ColumnNames())
		os << "," << c << "_ours," << c << "_ours_std," << c << "_paper";
	os << ",paper_garbled\n";
	for (const auto& L : table.levels)
		for (int q = 0; q < kTable1Quantities; ++q)
		{
			os << L.label << "," << table1QuantityNames()[q] << "," << L.runs;
			std::string garbled;
			for (int c = 0; c < kTable1Columns; ++c)
			{
				const TTable1Cell& cell = L.cells[q][c];
				const auto paper = paperTable1Value(L.label, q, c);
				os << "," << csvNumber(cell.mean) << "," << csvNumber(cell.std) << ","
				   << (paper ? csvNumber(*paper) : std::string());
				if (paperTable1Garbled(L.label, q, c))
					garbled += (garbled.empty() ? "" : ";") + table1ColumnNames()[c];
			}
			os << "," << garbled << "\n";
		}
}
}  // namespace dynslam::eval
