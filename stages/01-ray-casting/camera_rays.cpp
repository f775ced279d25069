#include "01-ray-casting/camera_rays.h"

#include "common/task.h"

namespace rt {

Ray generate_camera_ray(const PinholeCamera& camera, Vec2 film_point) {
  // BEGIN TASK stage1.camera.ray
  const float sx = (2.0f * film_point.x / float(camera.width) - 1.0f) * camera.aspect *
                   camera.tan_half_vfov;
  const float sy = (1.0f - 2.0f * film_point.y / float(camera.height)) * camera.tan_half_vfov;
  return Ray{camera.position, glm::normalize(camera.forward + sx * camera.right + sy * camera.up)};
  // PLACEHOLDER
  // report_unfinished_task("stage1.camera.ray");
  // (void)film_point;
  // return Ray{camera.position, camera.forward};
  // END TASK
}

}  // namespace rt
