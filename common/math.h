// Vector types and constants shared by every stage. GLM supplies the arithmetic; these aliases fix
// the precision (float everywhere unless a test shows float is not enough, see docs/design.md).
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace rt {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using DVec3 = glm::dvec3;
using Color = glm::vec3;  // linear RGB radiance, W sr^-1 m^-2 per channel

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Relative luminance of linear Rec. 709 / sRGB RGB (ITU-R BT.709 item 3.2; the sRGB standard's Y
// row): "how bright" as one number, for tone mapping and for comparing coloured lights' power.
inline float luminance(Color c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

inline float max_component(Vec3 v) { return std::max({v.x, v.y, v.z}); }
inline float min_component(Vec3 v) { return std::min({v.x, v.y, v.z}); }
// v[axis] for an axis known only at run time, read as an array element. GLM's operator[] is a
// switch, and selects (axis == 0 ? v.x : ...) compile to jumps too; the axis changes from ray to
// ray, so such jumps are often mispredicted (docs/stage5.md, the speed ladder, step 7).
inline float component(Vec3 v, int axis) {
  const float c[3] = {v.x, v.y, v.z};
  return c[axis];
}
// |v| per component. std::abs of a float clears the sign bit; glm::abs is written as
// x >= 0 ? x : -x, which GCC keeps as a compare and a jump on the sign.
inline Vec3 abs_components(Vec3 v) { return Vec3(std::abs(v.x), std::abs(v.y), std::abs(v.z)); }

inline bool is_finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The next float above (below) v: std::nextafter(v, +-inf) for every v but NaN, in a few
// instructions instead of a library call. Floats of one sign are ordered like their bit patterns,
// so one step in the bits is one step in value (up for positive v, down for negative v); -0 is
// first made +0, whose next float up is the smallest denormal; infinities stay (PBR 4th ed.,
// section 6.8.2, NextFloatUp).
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.0f) return v;
  if (v == 0.0f) v = 0.0f;  // -0 -> +0
  const auto bits = std::bit_cast<std::uint32_t>(v);
  return std::bit_cast<float>(v >= 0.0f ? bits + 1u : bits - 1u);
}
inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.0f) return v;
  if (v == 0.0f) v = -0.0f;  // +0 -> -0
  const auto bits = std::bit_cast<std::uint32_t>(v);
  return std::bit_cast<float>(v > 0.0f ? bits - 1u : bits + 1u);
}

// cos(theta) and sin(theta) for |theta| <= pi/4, by their Taylor series to degrees 8 and 9 in
// Horner form. The first terms left out, theta^10 / 10! and theta^11 / 11!, stay below 2.5e-8
// there, under half an ulp of the results (which lie in [0.7, 1] and [-0.71, 0.71]), and a few
// multiplications cost far less than std::cos and std::sin, which first reduce any angle to this
// range.
inline Vec2 cos_sin_quarter_turn(float theta) {
  const float t2 = theta * theta;
  const float c = 1.0f + t2 * (-1.0f / 2 + t2 * (1.0f / 24 + t2 * (-1.0f / 720 + t2 * (1.0f / 40320))));
  const float s = theta * (1.0f + t2 * (-1.0f / 6 + t2 * (1.0f / 120 + t2 * (-1.0f / 5040 + t2 * (1.0f / 362880)))));
  return Vec2(c, s);
}

// condition ? a : b computed from bit masks, with no jump. For a condition that is true or false at
// random (a random sample's case), a jump is mispredicted half the time, a stall of some 15 cycles
// each time; GCC compiles a plain ?: on floats to a jump when it also has to swap registers.
inline float select(bool condition, float a, float b) {
  const std::uint32_t mask = 0u - std::uint32_t(condition);
  return std::bit_cast<float>((std::bit_cast<std::uint32_t>(a) & mask) | (std::bit_cast<std::uint32_t>(b) & ~mask));
}

inline float radians(float degrees) { return degrees * (kPi / 180.0f); }

}  // namespace rt
