// A false-colour picture of a per-pixel count (the samples adaptive sampling spent on each pixel):
// black at 0, through blue, magenta and orange, to pale yellow at `most`, on a ramp whose steps look
// roughly even (its linear values rise with the square of the position).
#pragma once

#include "common/image.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace rt {

inline Color heat_colour(float fraction) {
  // Key colours at 0, 1/4, 1/2, 3/4 and 1 (sRGB-looking values, squared to linear below).
  static constexpr std::array<std::array<float, 3>, 5> kKeys{{
      {0.0f, 0.0f, 0.0f}, {0.2f, 0.1f, 0.6f}, {0.75f, 0.2f, 0.55f}, {0.98f, 0.55f, 0.15f}, {1.0f, 0.98f, 0.7f}}};
  const float x = std::clamp(fraction, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(int(x), 3);
  const float f = x - float(i);
  Color c;
  for (int k = 0; k < 3; ++k) {
    const float v = kKeys[size_t(i)][size_t(k)] + f * (kKeys[size_t(i) + 1][size_t(k)] - kKeys[size_t(i)][size_t(k)]);
    c[k] = v * v;
  }
  return c;
}

// counts row by row from the top, width x height of them.
inline Image heat_map(const std::vector<std::uint32_t>& counts, int width, int height, std::uint32_t most) {
  Image image(width, height);
  for (size_t i = 0; i < counts.size() && i < image.pixel_count(); ++i)
    image.pixels()[i] = heat_colour(most > 0 ? float(counts[i]) / float(most) : 0.0f);
  return image;
}

}  // namespace rt
