#include "07-vcm-mlt/primary_sample_space.h"

#include "common/task.h"

#include <cmath>

namespace rt {

namespace {
// The random streams of chain states (Rng's "pixel" argument): far above any pixel index.
constexpr std::uint64_t kChainStreams = std::uint64_t(1) << 62;
constexpr float kBelowOne = 0x1.fffffep-1f;
}  // namespace

PrimarySampleSpace::PrimarySampleSpace(std::uint64_t seed, std::uint64_t index, float sigma,
                                       float large_step_probability)
    : rng_(seed, kChainStreams + index, 0), sigma_(sigma), large_step_probability_(large_step_probability) {}

float small_step(float x, std::int64_t small_steps, float sigma, Vec2 u) {
  // BEGIN TASK stage7.mlt.mutate
  if (small_steps <= 0) return x;
  // Box-Muller: sqrt(-2 ln u1) cos(2 pi u2) is standard normal for u1 in (0, 1].
  const float normal = std::sqrt(-2.0f * std::log(1.0f - u.x)) * std::cos(2.0f * kPi * u.y);
  const float moved = x + normal * sigma * std::sqrt(float(small_steps));
  return std::min(moved - std::floor(moved), kBelowOne);
  // PLACEHOLDER
  // report_unfinished_task("stage7.mlt.mutate");
  // (void)small_steps, (void)sigma, (void)u;
  // return x;  // a chain that never moves
  // END TASK
}

void PrimarySampleSpace::start_iteration() {
  ++iteration_;
  large_step_ = rng_.uniform() < large_step_probability_;
  start_stream(camera);
}

void PrimarySampleSpace::start_stream(Stream stream) {
  stream_ = stream;
  stream_position_ = 0;
}

void PrimarySampleSpace::bring_up_to_date(Coordinate& x) {
  if (x.modified < last_large_step_) {
    // Untouched since the last accepted large step: that step made it fresh.
    x.value = rng_.uniform();
    x.modified = last_large_step_;
  }
  x.backup = x.value;
  x.backup_modified = x.modified;
  if (large_step_) {
    x.value = rng_.uniform();
  } else {
    const float u1 = rng_.uniform();
    x.value = small_step(x.value, iteration_ - x.modified, sigma_, Vec2(u1, rng_.uniform()));
  }
  x.modified = iteration_;
}

float PrimarySampleSpace::uniform() {
  const std::uint64_t i = stream_position_++ * kStreams + std::uint64_t(stream_);
  if (i >= x_.size()) x_.resize(i + 1);
  Coordinate& x = x_[i];
  bring_up_to_date(x);  // each coordinate is read once per iteration: streams never revisit one
  return x.value;
}

Vec2 PrimarySampleSpace::uniform2() {
  const float u = uniform();
  return Vec2(u, uniform());
}

void PrimarySampleSpace::accept() {
  // The proposal's coordinates stay; a large step's are fresh from here on.
  if (large_step_) last_large_step_ = iteration_;
}

void PrimarySampleSpace::reject() {
  for (Coordinate& x : x_)
    if (x.modified == iteration_) {
      x.value = x.backup;
      x.modified = x.backup_modified;
    }
  --iteration_;
}

}  // namespace rt
