// The sRGB transfer curve (IEC 61966-2-1): linear radiance to display values and back.
// PNG output goes through srgb_encode; everything the renderer computes stays linear.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rt {

// Linear [0, 1] -> encoded [0, 1]. The curve is linear near black (slope 12.92) and a 1/2.4 power
// above 0.0031308; a plain gamma of 2.2 is a different, wrong curve.
inline float srgb_encode(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // also maps NaN to black
  if (linear >= 1.0f) return 1.0f;
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

inline float srgb_decode(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Encoded value to an 8-bit code, rounding to nearest.
inline std::uint8_t srgb_to_byte(float linear) {
  return std::uint8_t(std::lround(255.0f * srgb_encode(linear)));
}

}  // namespace rt
