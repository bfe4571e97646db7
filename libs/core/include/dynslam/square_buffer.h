#pragma once
/** @file square_buffer.h
 * A square row-major matrix in a buffer that keeps its capacity, pure Eigen (doc/performance.md,
 * section 9). The filter's covariance changes size on most steps of a run (a new landmark, a
 * dropped pose): MRPT's CMatrixDynamic allocates a new buffer and zero-fills it twice on every
 * size change, and with glibc a growing sequence of blocks above the mmap threshold is mapped
 * fresh from the kernel each time (page faults). This buffer only grows, geometrically, and
 * leaves the contents of a resize unspecified (the caller writes every entry). Copying it is
 * not needed by the filter and not provided. */
#include <dynslam/ekf_steps.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>

namespace dynslam::ekf
{
class CSquareBuffer
{
public:
	using View = Eigen::Map<RowMatrixXd>;
	using ConstView = Eigen::Map<const RowMatrixXd>;

	/** n x n, contents unspecified. Reallocates (uninitialized) only if n^2 exceeds the
	 * capacity, or is under 1/16 of a capacity above 64^2 (after a compression: the buffer does
	 * not hoard the memory of a larger state); the new capacity is s^2 entries with s = n plus
	 * n/2 (at most 512), at least 64. */
	void resize(Eigen::Index n)
	{
		const size_t need = size_t(n) * size_t(n);
		if (need > m_capacity || (m_capacity > 64 * 64 && 16 * need < m_capacity))
		{
			const size_t side = std::max<size_t>(64, size_t(n) + std::min<size_t>(n / 2, 512));
			m_buf.reset();  // before the new one: never both at once
			m_buf.reset(new double[side * side]);
			m_capacity = side * side;
		}
		m_n = n;
	}
	/** Frees the buffer (size 0). */
	void release()
	{
		m_buf.reset();
		m_capacity = 0;
		m_n = 0;
	}
	Eigen::Index rows() const { return m_n; }
	View view() { return View(m_buf.get(), m_n, m_n); }
	ConstView view() const { return ConstView(m_buf.get(), m_n, m_n); }
	void swap(CSquareBuffer& o)
	{
		m_buf.swap(o.m_buf);
		std::swap(m_capacity, o.m_capacity);
		std::swap(m_n, o.m_n);
	}

private:
	std::unique_ptr<double[]> m_buf;
	size_t m_capacity = 0;
	Eigen::Index m_n = 0;
};
}  // namespace dynslam::ekf
