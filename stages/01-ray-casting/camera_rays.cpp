#include "01-ray-casting/camera_rays.h"

#include "01-ray-casting/disk_sampling.h"
#include "common/task.h"

namespace rt {

Ray generate_camera_ray(const Camera& camera, Vec2 film_point) {
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

Ray generate_lens_ray(const Camera& camera, Vec2 film_point, Vec2 lens_sample) {
  const Ray pinhole = generate_camera_ray(camera, film_point);
  // BEGIN TASK stage1.camera.thin_lens
  if (camera.aperture_radius == 0.0f) return pinhole;
  const Vec3 focus = pinhole.at(camera.focus_distance / glm::dot(pinhole.direction, camera.forward));
  const Vec2 lens = camera.aperture_radius * sample_uniform_disk(lens_sample);
  const Vec3 origin = camera.position + lens.x * camera.right + lens.y * camera.up;
  return Ray{origin, glm::normalize(focus - origin)};
  // PLACEHOLDER
  // report_unfinished_task("stage1.camera.thin_lens");
  // (void)lens_sample;
  // return pinhole;  // a pinhole: everything in focus
  // END TASK
}

}  // namespace rt
