// Vector types and constants shared by every stage. GLM supplies the arithmetic; these aliases fix
// the precision (float everywhere unless a test shows float is not enough, see docs/design.md).
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rt {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using DVec3 = glm::dvec3;
using Color = glm::vec3;  // linear RGB radiance, W sr^-1 m^-2 per channel

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

inline float max_component(Vec3 v) { return std::max({v.x, v.y, v.z}); }
inline float min_component(Vec3 v) { return std::min({v.x, v.y, v.z}); }
// v[axis] for an axis known only at run time. GLM's operator[] is a switch (a jump per call);
// two selects let the compiler use conditional moves instead.
inline float component(Vec3 v, int axis) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }

inline bool is_finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline float radians(float degrees) { return degrees * (kPi / 180.0f); }

}  // namespace rt
