// A ray o + t*d. By convention d is normalized, so t is a distance (docs/design.md).
#pragma once

#include "common/math.h"

namespace rt {

struct Ray {
  Vec3 origin;
  Vec3 direction;

  Vec3 at(float t) const { return origin + t * direction; }
};

}  // namespace rt
