#include "common/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace rt {

std::string format_si(double value) {
  const char* prefixes[] = {"", "k", "M", "G", "T"};
  int i = 0;
  while (std::abs(value) >= 1000.0 && i < 4) {
    value /= 1000.0;
    ++i;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %s", value, prefixes[i]);
  return text;
}

ProgressBar::ProgressBar(std::uint64_t total, std::string unit)
    : ProgressBar(total, std::move(unit), ::isatty(STDERR_FILENO) != 0) {}

ProgressBar::ProgressBar(std::uint64_t total, std::string unit, bool enabled)
    : total_(total), unit_(std::move(unit)), enabled_(enabled) {}

ProgressBar::~ProgressBar() {
  if (!finished_ && enabled_ && done() > 0) std::fputc('\n', stderr);
}

void ProgressBar::advance(std::uint64_t amount) {
  done_.fetch_add(amount, std::memory_order_relaxed);
  if (!enabled_) return;
  const std::int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
  std::int64_t last = last_draw_ns_.load(std::memory_order_relaxed);
  if (now - last < 100'000'000) return;
  if (!last_draw_ns_.compare_exchange_strong(last, now)) return;  // another thread draws
  std::unique_lock lock(draw_mutex_, std::try_to_lock);
  if (lock.owns_lock() && !finished_) draw(false);
}

void ProgressBar::finish() {
  std::lock_guard lock(draw_mutex_);
  if (finished_) return;
  finished_ = true;
  if (enabled_) draw(true);
}

void ProgressBar::draw(bool final_line) {
  const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
  const std::uint64_t done_now = final_line ? total_ : std::min(done(), total_);
  const double fraction = total_ > 0 ? double(done_now) / double(total_) : 1.0;
  const double rate = seconds > 0.0 ? double(done_now) / seconds : 0.0;
  constexpr int kWidth = 30;
  const int filled = int(fraction * kWidth);
  std::string bar(size_t(filled), '#');
  bar.resize(kWidth, '.');
  char tail[64];
  if (final_line)
    std::snprintf(tail, sizeof tail, "in %.1f s", seconds);
  else if (rate > 0.0)
    std::snprintf(tail, sizeof tail, "ETA %.0f s", double(total_ - done_now) / rate);
  else
    std::snprintf(tail, sizeof tail, "ETA --");
  std::fprintf(stderr, "\r[%s] %3.0f%%  %s%s/s  %s   ", bar.c_str(), 100.0 * fraction,
               format_si(rate).c_str(), unit_.c_str(), tail);
  if (final_line) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace rt
