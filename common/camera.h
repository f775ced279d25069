// The camera of docs/design.md: a pinhole, or a thin lens when the aperture is open. The camera is
// given; turning a film point (and a lens point) into a ray is the first task of stage 1
// (stages/01-ray-casting/camera_rays.h), which reads the fields below.
#pragma once

#include "common/math.h"

namespace rt {

struct CameraSpec {
  Vec3 position{0.0f};
  Vec3 look_at{0.0f, 0.0f, 1.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float vfov_degrees = 40.0f;  // VERTICAL field of view
  // The thin lens (stage 1, task stage1.camera.thin_lens): a disk of this radius, in scene units,
  // centred on `position` and facing `look_at`. 0 is a pinhole, where everything is sharp.
  float aperture_radius = 0.0f;
  // Distance, along the view direction, of the plane that is in focus; 0 = the distance to look_at.
  float focus_distance = 0.0f;
};

class Camera {
 public:
  // Throws std::invalid_argument when the spec has no defined frame (look_at == position, up
  // parallel to the view direction), the field of view is outside (0, 180) degrees, the aperture
  // is negative or the focus distance negative (each also when not finite).
  Camera(const CameraSpec& spec, int width, int height);

  Vec3 position;
  // forward = normalize(look_at - position), right = normalize(forward x up), up = right x forward.
  // A camera looking down +z with up +y therefore has +x on its LEFT (docs/design.md).
  Vec3 forward, right, up;
  float tan_half_vfov;  // half the film height at distance 1 from the pinhole
  float aspect;         // width / height
  int width, height;
  float aperture_radius;  // 0: a pinhole
  float focus_distance;   // > 0: the focal plane is {p : dot(p - position, forward) = focus_distance}
};

}  // namespace rt
