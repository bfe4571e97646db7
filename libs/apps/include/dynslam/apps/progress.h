#pragma once
/** @file progress.h
 * A thread-safe text progress bar for long runs (Monte Carlo sweeps), drawn on one line of a
 * stream (stderr by default) with '\r', redrawn at most every 0.1 s:
 *   [##########..........]  112/225 runs  3.1 s, ETA 3.0 s */
#include <chrono>
#include <iostream>
#include <mutex>
#include <string>

namespace dynslam::apps
{
class CProgressBar
{
public:
	CProgressBar(std::string unit, size_t total, std::ostream& os = std::cerr, bool enabled = true);
	~CProgressBar();
	/** Adds n finished items (any thread). */
	void advance(size_t n = 1);
	/** Draws the final state and ends the line (idempotent). */
	void finish();
	size_t done() const;
	/** The bar text for a given state (no '\r'), e.g. for tests. */
	static std::string format(size_t done, size_t total, double elapsed_s, const std::string& unit,
	                          int width = 30);

private:
	void drawLocked(bool force);
	std::string m_unit;
	size_t m_total, m_done = 0;
	std::ostream& m_os;
	bool m_enabled, m_finished = false;
	mutable std::mutex m_mtx;
	std::chrono::steady_clock::time_point m_start, m_lastDraw;
};
}  // namespace dynslam::apps
