// Stage 7: primary sample space (Kelemen, Szirmay-Kalos, Antal & Csonka, "A Simple and Robust
// Mutation Strategy for the Metropolis Light Transport Algorithm", Eurographics 2002). Every path
// sampler of this course is a function of the uniform numbers it draws: a path tracer or BDPT turns
// u = (u_1, u_2, ...) in the unit hypercube into a path and its contribution. Metropolis light
// transport can then run its Markov chain over u instead of over paths: a mutation perturbs the
// numbers, and the sampler, unchanged, turns them into a nearby path. This sampler is the chain's
// state. It hands out numbers like any Sampler, but each number is a coordinate of the current
// state, made lazily when first read:
//   - a large step replaces every coordinate by a fresh uniform number (an independent sample,
//     which keeps the chain ergodic);
//   - a small step moves each coordinate by a normal offset of deviation sigma, wrapped around
//     [0, 1): symmetric, T(u -> v) = T(v -> u), so the acceptance is the ratio of the targets.
// A coordinate not read for n small steps receives them all at once, an offset of deviation
// sigma sqrt(n) (the sum of n independent normal offsets), so a number a path reads only
// sometimes stays where the chain's history put it (pbrt-v3's MLTSampler keeps the same rule).
// Numbers come in streams (camera subpath, light subpath, connection), each its own sequence of
// coordinates, so a subpath that draws one number more does not shift what the other reads.
#pragma once

#include "common/random.h"

#include <cstdint>
#include <vector>

namespace rt {

class PrimarySampleSpace final : public Sampler {
 public:
  static constexpr int kStreams = 3;
  enum Stream { camera = 0, light = 1, connection = 2 };

  // The state of chain (or bootstrap sample) `index`: its coordinates and mutations come from its
  // own random stream, so the same index gives the same numbers in every run. Before the first
  // start_iteration it is a large step: the numbers read are an independent sample.
  PrimarySampleSpace(std::uint64_t seed, std::uint64_t index, float sigma, float large_step_probability);

  // A new proposal: a large step with probability large_step_probability, else a small step.
  void start_iteration();
  bool large_step() const { return large_step_; }
  // The numbers read next come from `stream`, from its first coordinate on.
  void start_stream(Stream stream);

  float uniform() override;
  Vec2 uniform2() override;

  // Keep the proposal as the new state, or return every coordinate it moved to where it was.
  void accept();
  void reject();

 private:
  struct Coordinate {
    float value = 0.0f;
    std::int64_t modified = 0;  // the iteration that last moved it
    float backup = 0.0f;
    std::int64_t backup_modified = 0;
  };
  // Brings a coordinate to the current iteration as it is read: fresh if the last accepted large
  // step came after it last moved, then this iteration's step.
  void bring_up_to_date(Coordinate& x);

  Rng rng_;
  float sigma_, large_step_probability_;
  std::vector<Coordinate> x_;
  std::int64_t iteration_ = 0, last_large_step_ = 0;
  bool large_step_ = true;
  int stream_ = 0;
  std::uint64_t stream_position_ = 0;
};

// Task stage7.mlt.mutate. Coordinate value x after `small_steps` small steps of deviation sigma
// (normal offsets, their sum wrapped around [0, 1)), from the two uniform numbers u that make one
// standard normal number (Box–Muller); small_steps = 0 leaves it. Never returns 1.
float small_step(float x, std::int64_t small_steps, float sigma, Vec2 u);

}  // namespace rt
