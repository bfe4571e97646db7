#pragma once
/** @file square_buffer.h
 * A square row-major matrix in a buffer that keeps its capacity, pure Eigen
 * (doc/results/performance.md, sections 9 and 10). The filter's covariance changes size on most
 * steps of a run (a new landmark, a dropped pose). The buffer is a side x side row-major array
 * (side >= n, the outer stride of the view, fixed until the next reallocation), so the n x n matrix
 * can grow and shrink in place: new entries are written after the old block without moving it,
 * drops are compacted towards the top-left corner (ekf::assembleInPlace). It reallocates only when
 * n outgrows the side, geometrically. Freed buffers are kept in a small per-thread cache and handed
 * to the next buffer of that thread (a Monte Carlo sweep runs one filter after the other: no fresh
 * pages from the kernel per run). Copying is not needed by the filter and not provided. */
#include <dynslam/core/ekf_steps.h>

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <utility>

namespace dynslam::ekf
{
class CSquareBuffer
{
public:
	using View = Eigen::Map<RowMatrixXd, Eigen::Unaligned, Eigen::OuterStride<>>;
	using ConstView = Eigen::Map<const RowMatrixXd, Eigen::Unaligned, Eigen::OuterStride<>>;

	CSquareBuffer() = default;
	CSquareBuffer(const CSquareBuffer&) = delete;
	CSquareBuffer& operator=(const CSquareBuffer&) = delete;
	~CSquareBuffer() { release(); }

	/** Whether resize(n) keeps the buffer (and so the entries of the top-left block of
	 * min(n, rows()) that it had): n fits the side, and n^2 is not under 1/16 of a buffer
	 * above 64^2 (after a compression: the buffer does not hoard the memory of a larger
	 * state). */
	bool keeps(Eigen::Index n) const { return fits(m_side, n); }
	/** Whether a buffer of this side keeps size n (see keeps()). */
	static bool fits(size_t side, Eigen::Index n)
	{
		const size_t need = size_t(n) * size_t(n), cap = side * side;
		return size_t(n) <= side && !(cap > 64 * 64 && 16 * need < cap);
	}
	/** n x n. Keeps the buffer if keeps(n), with its contents; otherwise reallocates with
	 * side n plus n/2 (at most 512), at least 64, contents unspecified. */
	void resize(Eigen::Index n);
	/** Frees the buffer (size 0; into the thread's cache). */
	void release();
	Eigen::Index rows() const { return m_n; }
	/** The outer stride of the view (the buffer's side). */
	Eigen::Index stride() const { return Eigen::Index(m_side); }
	double* data() { return m_buf.get(); }
	View view() { return View(m_buf.get(), m_n, m_n, Eigen::OuterStride<>(stride())); }
	ConstView view() const
	{
		return ConstView(m_buf.get(), m_n, m_n, Eigen::OuterStride<>(stride()));
	}
	void swap(CSquareBuffer& o)
	{
		m_buf.swap(o.m_buf);
		std::swap(m_side, o.m_side);
		std::swap(m_n, o.m_n);
	}

private:
	std::unique_ptr<double[]> m_buf;
	size_t m_side = 0;
	Eigen::Index m_n = 0;
};
}  // namespace dynslam::ekf
