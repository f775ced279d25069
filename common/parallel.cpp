#include "common/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rt {

int resolve_thread_count(int threads) {
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallel_for(int count, int threads, const std::function<void(int)>& body) {
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;

  auto worker = [&] {
    for (int i = next++; i < count && !failed; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
      }
    }
  };

  const int workers = std::min(resolve_thread_count(threads), std::max(count, 1));
  std::vector<std::jthread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(worker);
  worker();  // the calling thread works too
  pool.clear();  // joins
  if (first_error) std::rethrow_exception(first_error);
}

void parallel_for_tiles(int width, int height, int threads,
                        const std::function<void(const PixelRect&)>& body) {
  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int tiles_y = (height + kTileSize - 1) / kTileSize;
  parallel_for(tiles_x * tiles_y, threads, [&](int i) {
    const int tx = i % tiles_x, ty = i / tiles_x;
    body(PixelRect{tx * kTileSize, ty * kTileSize, std::min(width, (tx + 1) * kTileSize),
                   std::min(height, (ty + 1) * kTileSize)});
  });
}

void for_each_chunk(size_t count, int threads, const std::function<void(size_t, size_t)>& body) {
  // Starting a thread costs tens of microseconds: a chunk of fewer indices is not worth one.
  constexpr size_t kMinChunk = 1024;
  const size_t chunks = std::max<size_t>(1, std::min(size_t(resolve_thread_count(threads)), count / kMinChunk));
  std::vector<std::future<void>> others;
  for (size_t c = 0; c + 1 < chunks; ++c)
    others.push_back(start_on_thread([&body, begin = count * c / chunks, end = count * (c + 1) / chunks] { body(begin, end); }));
  body(count * (chunks - 1) / chunks, count);
  for (std::future<void>& other : others) other.get();
}

}  // namespace rt
