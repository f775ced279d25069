// The project's threads, in one place. The tile scheduler splits an image into square tiles and
// hands them to worker threads from a shared counter, so fast tiles do not wait for slow ones;
// for_each_chunk cuts an index range into one contiguous chunk per thread (a BVH build's chunks).
// Which thread renders which tile varies from run to run; renders stay deterministic because random
// numbers depend only on (seed, pixel, sample), see common/random.h.
#pragma once

#include "common/image.h"

#include <cstddef>
#include <functional>
#include <future>
#include <system_error>

namespace rt {

inline constexpr int kTileSize = 16;

// Calls body(tile) once for every tile (a PixelRect) of a width x height image on `threads` threads
// (0 = all cores). The first exception thrown by a body stops the remaining tiles and is rethrown
// here.
void parallel_for_tiles(int width, int height, int threads,
                        const std::function<void(const PixelRect&)>& body);

// Calls body(i) once for every i in [0, count) on `threads` threads (0 = all cores), handing out the
// indices from a shared counter; the same error rule. parallel_for_tiles is this over the tiles,
// numbered row by row: a caller that keeps one result per tile can combine them in that order.
void parallel_for(int count, int threads, const std::function<void(int)>& body);

// Number of threads `threads` stands for (0 = all cores, at least 1).
int resolve_thread_count(int threads);

// `task` on a thread of its own; where no thread is to be had, the future's get() runs it.
template <class Task>
auto start_on_thread(Task task) -> std::future<decltype(task())> {
  try {
    return std::async(std::launch::async, task);
  } catch (const std::system_error&) {
    return std::async(std::launch::deferred, task);
  }
}

// Calls body(begin, end) for `threads` contiguous chunks of [0, count) at the same time, each on a
// thread of its own (0: one per core; fewer where a chunk would hold under 1,024 indices; the
// calling thread takes the last chunk). The chunks depend on the thread count, so what body makes
// of an index must not.
void for_each_chunk(size_t count, int threads, const std::function<void(size_t begin, size_t end)>& body);

}  // namespace rt
