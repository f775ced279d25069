// An axis-aligned bounding box: what every bounded primitive kind reports (stage 2) and what the
// BVH is built from (stage 3, whose lecture is the slab test against it: 03-acceleration/aabb.h).
#pragma once

#include "common/math.h"

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

namespace rt {

struct Aabb {
  Vec3 lo{kInfinity};  // the default box is empty: lo > hi
  Vec3 hi{-kInfinity};

  void expand(Vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void expand(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool is_empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  Vec3 extent() const { return hi - lo; }
  Vec3 centroid() const { return 0.5f * (lo + hi); }
  bool contains(const Aabb& b) const {
    return b.is_empty() || (glm::all(glm::lessThanEqual(lo, b.lo)) && glm::all(glm::lessThanEqual(b.hi, hi)));
  }
  // Half the surface area is all the SAH needs (it compares ratios); 0 for an empty box.
  float half_area() const {
    if (is_empty()) return 0.0f;
    const Vec3 e = extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
  int longest_axis() const {
    const Vec3 e = extent();
    return e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
  }
};

}  // namespace rt
