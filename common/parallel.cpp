#include "common/parallel.h"

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

}  // namespace rt
