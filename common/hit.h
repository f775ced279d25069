// What an intersection reports, the same record for every shape in every stage.
#pragma once

#include "common/math.h"
#include "common/ray.h"

namespace rt {

struct Hit {
  float t = kInfinity;
  Vec3 point{0.0f};
  // Unit normal on the side the ray came from (opposite the ray), so shading never has to ask
  // which side it is on; front_face records whether that is the outward side.
  Vec3 normal{0.0f};
  bool front_face = true;
  int material = -1;
  int primitive = -1;  // index of the shape in its scene, for debug output and tests

  // The front-face rule, in one place: the ray hits the front (outward) side when it travels
  // against the outward normal.
  void set_face_normal(const Ray& ray, Vec3 outward_normal) {
    front_face = glm::dot(ray.direction, outward_normal) < 0.0f;
    normal = front_face ? outward_normal : -outward_normal;
  }
};

}  // namespace rt
