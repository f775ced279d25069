// A progress bar for long work: percentage, rate and ETA on one self-overwriting line of stderr
// when stderr is a terminal, nothing at all otherwise (logs and CI stay clean).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace rt {

class ProgressBar {
 public:
  // `unit` names what is counted, e.g. "samples"; `enabled` defaults to "stderr is a terminal".
  ProgressBar(std::uint64_t total, std::string unit);
  ProgressBar(std::uint64_t total, std::string unit, bool enabled);
  ~ProgressBar();

  // Thread-safe; redraws at most every 100 ms, and never blocks a caller on the drawing.
  void advance(std::uint64_t amount);
  // Draws the final line (100%, total time, mean rate) and ends it.
  void finish();

  std::uint64_t done() const { return done_.load(std::memory_order_relaxed); }

 private:
  void draw(bool final_line);

  using Clock = std::chrono::steady_clock;
  const std::uint64_t total_;
  const std::string unit_;
  const bool enabled_;
  const Clock::time_point start_ = Clock::now();
  std::atomic<std::uint64_t> done_{0};
  std::atomic<std::int64_t> last_draw_ns_{0};
  std::mutex draw_mutex_;
  bool finished_ = false;
};

// "1.23 M" style formatting of a rate, shared by progress output and the stage programs' reports.
std::string format_si(double value);

}  // namespace rt
