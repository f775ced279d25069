// Random numbers for rendering: one PCG32 stream per (seed, pixel), positioned at the sample index.
//
// Every sample's numbers are a pure function of (seed, pixel, sample index), never of the thread or
// tile that computes it, so a render is bit-identical for any thread count. This is pbrt-v4's
// IndependentSampler scheme: stream chosen by a hash of (pixel, seed), then Advance(sample * 2^16).
// Consecutive stream ids are hashed first because PCG streams with nearby increments are
// correlated (O'Neill 2014; the same reason Mitsuba 3 hashes its chi^2 seeds).
#pragma once

#include "common/math.h"

#include <pcg_random.hpp>

#include <concepts>
#include <cstdint>

namespace rt {

// Where an integrator draws its numbers from: independent random numbers (Rng) or a
// low-discrepancy sequence (stage 5). Two calls, one number or a pair; the pair is one point of a
// 2D pattern, so a sampler that stratifies in 2D keeps the two coordinates together.
class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual float uniform() = 0;
  virtual Vec2 uniform2() = 0;
};

// A concrete sampler type (Rng, stage 5's SobolSampler) as an integrator's template parameter: its
// calls inline, where a Sampler& costs a virtual call per number.
template <class T>
concept SamplerType = std::derived_from<T, Sampler>;

class Rng final : public Sampler {
 public:
  // Each sample may draw up to this many numbers before it runs into the next sample's.
  static constexpr std::uint64_t kDimensionsPerSample = std::uint64_t(1) << 16;

  Rng(std::uint64_t seed, std::uint64_t pixel_index, std::uint64_t sample_index)
      : engine_(mix(seed), mix(pixel_index ^ mix(seed + 0x9e3779b97f4a7c15ull))) {
    engine_.advance(sample_index * kDimensionsPerSample);
  }

  std::uint32_t next_u32() { return engine_(); }

  // Uniform in [0, 1): the top 24 bits scaled by 2^-24, so the result is exactly representable
  // and never rounds up to 1 (std::uniform_real_distribution<float> can return 1, LWG 2524).
  float uniform() override { return float(engine_() >> 8) * 0x1p-24f; }
  Vec2 uniform2() override {
    const float u = uniform();
    return Vec2(u, uniform());
  }

  // The 64-bit finalizer of MurmurHash3 (Appleby): a bijection that spreads every input bit over
  // the whole output.
  static constexpr std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    x ^= x >> 33;
    return x;
  }

 private:
  pcg32 engine_;
};

}  // namespace rt
