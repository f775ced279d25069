#include "common/task.h"

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>

namespace rt {

namespace {

// The addresses of ids already reported, so that a placeholder in a hot loop (the slab test, a
// triangle test, a sampler's hash: millions of calls a second on every thread) costs one load
// after its first call instead of a lock and a set lookup. Measured: with the Owen scramble's
// placeholder, stage 5's convergence test took 8.0 s through the lock and 1.5 s with the table.
// Open addressing on the address; written only under the lock, read without it (a reader that
// misses an entry being written takes the slow path, which answers right).
constexpr std::size_t kSlots = 256;
std::atomic<const char*> reported_addresses[kSlots];

std::size_t home_slot(const char* task_id) { return (reinterpret_cast<std::uintptr_t>(task_id) >> 4) % kSlots; }

bool address_reported(const char* task_id) {
  for (std::size_t i = 0, slot = home_slot(task_id); i < kSlots; ++i, slot = (slot + 1) % kSlots) {
    const char* address = reported_addresses[slot].load(std::memory_order_acquire);
    if (address == task_id) return true;
    if (address == nullptr) return false;
  }
  return false;
}

// Called under the lock. A full table (more than kSlots distinct addresses) only loses speed.
void remember_address(const char* task_id) {
  for (std::size_t i = 0, slot = home_slot(task_id); i < kSlots; ++i, slot = (slot + 1) % kSlots) {
    const char* address = reported_addresses[slot].load(std::memory_order_relaxed);
    if (address == task_id) return;
    if (address == nullptr) {
      reported_addresses[slot].store(task_id, std::memory_order_release);
      return;
    }
  }
}

}  // namespace

bool report_unfinished_task(const char* task_id) {
  if (address_reported(task_id)) return false;
  // By content: the same id from two files may be two string literals at two addresses.
  static std::mutex mutex;
  static std::set<std::string> reported;
  std::lock_guard lock(mutex);
  const bool first = reported.insert(task_id).second;
  if (first)
    std::fprintf(stderr, "TODO: task %s is not implemented yet (see docs/ for the stage handout)\n", task_id);
  remember_address(task_id);
  return first;
}

}  // namespace rt
