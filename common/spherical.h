// Directions as points of the latitude-longitude map, the parametrization a sphere's texture
// coordinates and an environment map share. With theta the angle from +y (straight up) and phi
// the angle about +y from +x towards +z,
//     d = (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi)),
//     u = phi / (2 pi) in [0, 1),   v = 1 - theta / pi in [0, 1]   (v runs up, as texture v does).
// Seen from inside (an environment), u grows to the right of a viewer who stands upright.
#pragma once

#include "common/math.h"

#include <cmath>

namespace rt {

// theta from atan2 of the two legs, not acos(d.y): acos loses every digit near the poles, where
// d.y rounds to 1.
inline Vec2 latlong_uv(Vec3 d) {
  const float theta = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
  float phi = std::atan2(d.z, d.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  const float u = phi * (0.5f * kInvPi);
  return Vec2(u < 1.0f ? u : 0.0f, 1.0f - theta * kInvPi);  // phi just under 2 pi may round u up to 1
}

inline Vec3 latlong_direction(Vec2 uv) {
  const float theta = (1.0f - uv.y) * kPi, phi = uv.x * 2.0f * kPi;
  const float sin_theta = std::sin(theta);
  return Vec3(sin_theta * std::cos(phi), std::cos(theta), sin_theta * std::sin(phi));
}

}  // namespace rt
