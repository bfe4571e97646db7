#pragma once
/** @file progress.h
 * A thread-safe progress display for long runs (Monte Carlo sweeps). On a terminal it is a bar
 * drawn on one line with '\r', redrawn at most every 0.1 s:
 *   [##########..........]  112/225 runs  3.1 s, ETA 3.0 s
 * Into a file or pipe (a redirected log, a batch job) it writes no '\r' and no bar: one plain
 * line each time another tenth of the work is done:
 *   112/225 runs (50%)  3.1 s, ETA 3.0 s */
#include <chrono>
#include <iostream>
#include <mutex>
#include <string>

namespace dynslam::apps
{
class CProgressBar
{
public:
	enum class Style
	{
		Auto,  ///< Bar if the stream is std::cerr / std::cout on a terminal, else Lines
		Bar,
		Lines
	};
	CProgressBar(std::string unit, size_t total, std::ostream& os = std::cerr, bool enabled = true,
	             Style style = Style::Auto);
	~CProgressBar();
	/** Adds n finished items (any thread). */
	void advance(size_t n = 1);
	/** Draws the final state and ends the line (idempotent). */
	void finish();
	size_t done() const;
	/** The style in use (Auto resolved). */
	Style style() const { return m_style; }
	/** The bar text for a given state (no '\r'), e.g. for tests. */
	static std::string format(size_t done, size_t total, double elapsed_s, const std::string& unit,
	                          int width = 30);
	/** The plain-line text (Lines style). */
	static std::string formatLine(size_t done, size_t total, double elapsed_s,
	                              const std::string& unit);
	/** True if `os` is std::cerr or std::cout and that file descriptor is a terminal. */
	static bool isTerminal(const std::ostream& os);

private:
	void drawLocked(bool force);
	std::string m_unit;
	size_t m_total, m_done = 0;
	std::ostream& m_os;
	bool m_enabled, m_finished = false;
	Style m_style;
	size_t m_lastTenth = 0;  ///< Lines: tenths already reported
	mutable std::mutex m_mtx;
	std::chrono::steady_clock::time_point m_start, m_lastDraw;
};
}  // namespace dynslam::apps
