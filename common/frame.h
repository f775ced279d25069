// An orthonormal frame (s, t, n): turns world directions into a local frame where the normal is +z,
// which is where BRDFs and hemisphere warps are written.
#pragma once

#include "common/math.h"

namespace rt {

struct Frame {
  Vec3 s, t, n;

  // Completes a unit normal n to a right-handed orthonormal basis without branching on a
  // threshold, so the basis is continuous except where n.z changes sign.
  // Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017, Listing 3.
  static Frame from_normal(Vec3 n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return Frame{Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
                 Vec3(b, sign + n.y * n.y * a, -n.y), n};
  }

  Vec3 to_local(Vec3 v) const { return Vec3(glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)); }
  Vec3 to_world(Vec3 v) const { return v.x * s + v.y * t + v.z * n; }
};

// The mirror direction of w about the local normal +z, in the local frame: r = 2 (w.n) n - w.
inline Vec3 mirror_local(Vec3 w) { return Vec3(-w.x, -w.y, w.z); }

}  // namespace rt
