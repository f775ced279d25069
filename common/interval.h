// A range of ray parameters. Rays are valid for t in the OPEN interval (min, max); using one type
// instead of loose t_min/t_max pairs keeps "strictly inside" and "shrink to the nearest hit" in one
// place.
#pragma once

#include "common/math.h"

namespace rt {

struct Interval {
  float min = kInfinity;  // the default interval is empty
  float max = -kInfinity;

  // Strictly inside: the test for a valid hit distance.
  bool surrounds(float t) const { return min < t && t < max; }
  bool contains(float t) const { return min <= t && t <= max; }
  bool is_empty() const { return !(min < max); }

  // Everything in front of the ray origin: (0, +inf).
  static constexpr Interval positive() { return Interval{0.0f, kInfinity}; }
};

}  // namespace rt
