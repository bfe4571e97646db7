/** CSquareBuffer (dynslam/core/square_buffer.h): the allocation and the per-thread cache of freed
 * buffers. */
#include <dynslam/core/square_buffer.h>

#include <algorithm>
#include <vector>

namespace dynslam::ekf
{
namespace
{
/** Freed buffers of this thread, for the next buffer of the thread: at most kSlots buffers,
 * each of at most kMaxEntries doubles (larger ones go back to the system). */
struct TBufferCache
{
	static constexpr size_t kSlots = 4;
	static constexpr size_t kMaxEntries = size_t(1) << 22;           // 32 MiB
	std::vector<std::pair<size_t, std::unique_ptr<double[]>>> free;  ///< (side, buffer)
};
// A plain pointer (no destructor) owned by t_owner: a buffer freed after the thread's cache
// was destroyed (a static filter at exit) is simply freed.
thread_local TBufferCache* t_cache = nullptr;
thread_local bool t_cacheGone = false;
struct TCacheOwner
{
	~TCacheOwner()
	{
		delete t_cache;
		t_cache = nullptr;
		t_cacheGone = true;
	}
};
thread_local TCacheOwner t_owner;
TBufferCache* threadCache()
{
	if (!t_cache && !t_cacheGone)
	{
		(void)&t_owner;  // constructs it: it deletes the cache at thread exit
		t_cache = new TBufferCache;
	}
	return t_cache;
}

/** Sides are multiples of 8 doubles (64 bytes), so every row of every buffer starts at the same
 * alignment (new double[] is 16-byte aligned): whichever buffer a filter gets, Eigen's
 * vectorized loops split a row the same way, so the arithmetic does not depend on it. */
size_t roundSide(size_t s) { return (s + 7) / 8 * 8; }
}  // namespace

void CSquareBuffer::resize(Eigen::Index n)
{
	if (keeps(n))
	{
		m_n = n;
		return;
	}
	release();
	m_n = n;
	if (TBufferCache* c = threadCache())
	{
		// The smallest cached buffer that keeps this size.
		auto& cache = c->free;
		auto best = cache.end();
		for (auto it = cache.begin(); it != cache.end(); ++it)
			if (fits(it->first, n) && (best == cache.end() || it->first < best->first)) best = it;
		if (best != cache.end())
		{
			m_side = best->first;
			m_buf = std::move(best->second);
			cache.erase(best);
			return;
		}
	}
	m_side = roundSide(std::max<size_t>(64, size_t(n) + std::min<size_t>(size_t(n) / 2, 512)));
	m_buf.reset(new double[m_side * m_side]);
}

void CSquareBuffer::release()
{
	TBufferCache* c = m_buf ? threadCache() : nullptr;
	if (c && m_side * m_side <= TBufferCache::kMaxEntries)
	{
		auto& cache = c->free;
		if (cache.size() >= TBufferCache::kSlots)  // drop the smallest
			cache.erase(std::min_element(cache.begin(), cache.end(),
			                             [](const auto& a, const auto& b)
			                             { return a.first < b.first; }));
		cache.emplace_back(m_side, std::move(m_buf));
	}
	m_buf.reset();
	m_side = 0;
	m_n = 0;
}
}  // namespace dynslam::ekf
