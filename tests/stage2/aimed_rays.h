// Random rays for comparing two triangle tests answer for answer (triangle_lanes_test.cpp,
// triangle_pack_test.cpp): aimed at a point of a triangle's plane in and around it, from every
// side, with the cases where the tests' arithmetic is delicate mixed in.
#pragma once

#include "common/interval.h"
#include "common/random.h"
#include "common/ray.h"

#include <cmath>
#include <optional>

namespace rt {

inline Vec3 random_point(Rng& rng) { return Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f; }

struct AimedRay {
  Ray ray;
  Interval range;
};

// Case i of a run, for a triangle of about `size`: barycentrics of the target in [-0.25, 1.25]; a
// sixth of the directions with one or two components exactly 0 (so every permutation of the axes,
// and the flip of kx and ky for a negative d_kz, is taken); every fourth ray starting on the
// triangle, give or take a few roundings (a secondary ray), where t is rounding noise and the bound
// on t decides; every fifth range ending before the hit. Nothing when the direction came out 0.
inline std::optional<AimedRay> aimed_ray(Rng& rng, int i, Vec3 v0, Vec3 v1, Vec3 v2, float size) {
  const float b1 = 1.5f * rng.uniform() - 0.25f, b2 = 1.5f * rng.uniform() - 0.25f;
  const Vec3 target = (1.0f - b1 - b2) * v0 + b1 * v1 + b2 * v2;
  Vec3 direction = random_point(rng);
  if (i % 6 == 0) direction[i / 6 % 3] = 0.0f;
  if (i % 12 == 0) direction[(i / 6 + 1) % 3] = -0.0f;
  if (glm::dot(direction, direction) == 0.0f) return std::nullopt;
  direction = glm::normalize(direction);
  const float distance = i % 4 == 0 ? size * 1e-6f * rng.uniform() : size * std::pow(10.0f, 2.0f * rng.uniform());
  const Interval range = i % 5 == 0 ? Interval{0.0f, distance * rng.uniform()} : Interval::positive();
  return AimedRay{Ray{target - distance * direction, direction}, range};
}

}  // namespace rt
