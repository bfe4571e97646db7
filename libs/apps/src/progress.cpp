#include <dynslam/apps/progress.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace dynslam::apps
{
bool CProgressBar::isTerminal(const std::ostream& os)
{
	if (&os == &std::cerr || &os == &std::clog) return ::isatty(STDERR_FILENO) == 1;
	if (&os == &std::cout) return ::isatty(STDOUT_FILENO) == 1;
	return false;
}

CProgressBar::CProgressBar(std::string unit, size_t total, std::ostream& os, bool enabled,
                           Style style)
    : m_unit(std::move(unit)),
      m_total(total),
      m_os(os),
      m_enabled(enabled),
      m_style(style == Style::Auto ? (isTerminal(os) ? Style::Bar : Style::Lines) : style),
      m_start(std::chrono::steady_clock::now()),
      m_lastDraw(m_start)
{
	std::lock_guard<std::mutex> lk(m_mtx);
	if (m_style == Style::Bar) drawLocked(true);
}

CProgressBar::~CProgressBar() { finish(); }

size_t CProgressBar::done() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	return m_done;
}

void CProgressBar::advance(size_t n)
{
	std::lock_guard<std::mutex> lk(m_mtx);
	m_done = std::min(m_total, m_done + n);
	drawLocked(m_done == m_total);
}

void CProgressBar::finish()
{
	std::lock_guard<std::mutex> lk(m_mtx);
	if (m_finished) return;
	if (m_style == Style::Bar)
	{
		if (m_done != m_total) drawLocked(true);  // advance() drew the complete bar already
		if (m_enabled) m_os << "\n" << std::flush;
	}
	m_finished = true;
}

std::string CProgressBar::format(size_t done, size_t total, double elapsed_s,
                                 const std::string& unit, int width)
{
	const double frac = total ? double(done) / double(total) : 1.0;
	const int filled = int(frac * width + 1e-9);
	std::ostringstream os;
	os << "[" << std::string(size_t(filled), '#') << std::string(size_t(width - filled), '.')
	   << "] ";
	char buf[96];
	std::snprintf(buf, sizeof(buf), "%*zu/%zu %s  %.1f s", int(std::to_string(total).size()), done,
	              total, unit.c_str(), elapsed_s);
	os << buf;
	if (done > 0 && done < total)
	{
		std::snprintf(buf, sizeof(buf), ", ETA %.1f s",
		              elapsed_s / double(done) * double(total - done));
		os << buf;
	}
	return os.str();
}

std::string CProgressBar::formatLine(size_t done, size_t total, double elapsed_s,
                                     const std::string& unit)
{
	char buf[128];
	std::snprintf(buf, sizeof(buf), "%zu/%zu %s (%.0f%%)  %.1f s", done, total, unit.c_str(),
	              total ? 100.0 * double(done) / double(total) : 100.0, elapsed_s);
	std::string s = buf;
	if (done > 0 && done < total)
	{
		std::snprintf(buf, sizeof(buf), ", ETA %.1f s",
		              elapsed_s / double(done) * double(total - done));
		s += buf;
	}
	return s;
}

void CProgressBar::drawLocked(bool force)
{
	if (!m_enabled || m_finished) return;
	const auto now = std::chrono::steady_clock::now();
	const double el = std::chrono::duration<double>(now - m_start).count();
	if (m_style == Style::Lines)
	{
		// One line per completed tenth (and the last one), never '\r'.
		const size_t tenth = m_total ? m_done * 10 / m_total : 10;
		if (tenth <= m_lastTenth) return;
		m_lastTenth = tenth;
		m_os << formatLine(m_done, m_total, el, m_unit) << "\n" << std::flush;
		return;
	}
	if (!force && now - m_lastDraw < std::chrono::milliseconds(100)) return;
	m_lastDraw = now;
	m_os << "\r" << format(m_done, m_total, el, m_unit) << "   " << std::flush;
}
}  // namespace dynslam::apps
