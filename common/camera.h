// The pinhole camera of docs/design.md. The camera is given; turning a film point into a ray is the
// first task of stage 1 (stages/01-ray-casting/camera_rays.h), which reads the fields below.
#pragma once

#include "common/math.h"

namespace rt {

struct CameraSpec {
  Vec3 position{0.0f};
  Vec3 look_at{0.0f, 0.0f, 1.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float vfov_degrees = 40.0f;  // VERTICAL field of view
};

class PinholeCamera {
 public:
  // Throws std::invalid_argument when the spec has no defined frame (look_at == position, up
  // parallel to the view direction) or the field of view is outside (0, 180) degrees.
  PinholeCamera(const CameraSpec& spec, int width, int height);

  Vec3 position;
  // forward = normalize(look_at - position), right = normalize(forward x up), up = right x forward.
  // A camera looking down +z with up +y therefore has +x on its LEFT (docs/design.md).
  Vec3 forward, right, up;
  float tan_half_vfov;  // half the film height at distance 1 from the pinhole
  float aspect;         // width / height
  int width, height;
};

}  // namespace rt
