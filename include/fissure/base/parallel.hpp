#pragma once
/// Deterministic parallel loops. Work items write into slots indexed by item and are reduced in
/// index order by the caller, so the thread count changes speed, never results.

#include <cstddef>
#include <functional>

namespace fissure {

/// Calls body(i) for i in [0, count) on min(`threads`, thread_count()) threads (≤ 1: the calling
/// thread only; thread_count.hpp), in contiguous static blocks. If bodies throw, the exception of the lowest failing index is
/// rethrown after every thread has finished.
void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& body);

/// As parallel_for, but each thread takes the next undone item (ascending) when it is free, for
/// items whose costs differ by orders of magnitude (fit trials: 3 ms to 600 ms). Results are as
/// deterministic as the bodies' slots; after a body throws, no new item starts, and the
/// exception of the lowest failing index is rethrown once every thread has finished.
void parallel_for_dynamic(std::size_t count, int threads, const std::function<void(std::size_t)>& body);

/// The number of hardware threads, at least 1.
int hardware_threads();

}  // namespace fissure
