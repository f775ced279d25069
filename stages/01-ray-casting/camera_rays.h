// Stage 1, task stage1.camera.ray: from a point on the film to a ray through the pinhole.
#pragma once

#include "common/camera.h"
#include "common/ray.h"

namespace rt {

// `film_point` is in pixel units: (0, 0) is the top-left corner of the image, (width, height) the
// bottom-right corner, so pixel (x, y) covers [x, x+1) x [y, y+1) and its centre is (x+.5, y+.5).
// Returns the ray from the camera position through that point, with a normalized direction.
//
// The film sits at distance 1 in front of the pinhole. Its half height is tan(vfov / 2) and its half
// width is aspect times that, so the point maps to
//   s_x = (2 x / W - 1) * aspect * tan(vfov/2),   s_y = (1 - 2 y / H) * tan(vfov/2)
//   d   = normalize(forward + s_x * right + s_y * up)
// (s_y flips sign because image rows grow downwards while `up` points up).
Ray generate_camera_ray(const PinholeCamera& camera, Vec2 film_point);

}  // namespace rt
