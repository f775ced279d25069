#include "06-light-transport/camera_importance.h"

#include "common/task.h"

namespace rt {

float film_area(const Camera& camera) {
  const float height = 2.0f * camera.tan_half_vfov;
  return height * height * camera.aspect;
}

std::optional<Vec2> project_to_film(const Camera& camera, Vec3 p) {
  // BEGIN TASK stage6.camera.project
  // Stage 1 sends the ray through forward + sx right + sy up; here p - position is scaled to meet
  // the film plane at distance 1, and (sx, sy) are read off and mapped back to pixels.
  const Vec3 d = p - camera.position;
  const float z = glm::dot(d, camera.forward);
  if (!(z > 0.0f)) return std::nullopt;
  const float sx = glm::dot(d, camera.right) / z, sy = glm::dot(d, camera.up) / z;
  const Vec2 film((sx / (camera.aspect * camera.tan_half_vfov) + 1.0f) * 0.5f * float(camera.width),
                  (1.0f - sy / camera.tan_half_vfov) * 0.5f * float(camera.height));
  if (!(film.x >= 0.0f && film.x < float(camera.width) && film.y >= 0.0f && film.y < float(camera.height)))
    return std::nullopt;
  return film;
  // PLACEHOLDER
  // report_unfinished_task("stage6.camera.project");
  // (void)camera, (void)p;
  // return std::nullopt;  // nothing is seen: light tracing adds nothing
  // END TASK
}

float camera_importance(const Camera& camera, Vec3 w) {
  // BEGIN TASK stage6.camera.importance
  if (!project_to_film(camera, camera.position + w)) return 0.0f;
  const float cos_theta = glm::dot(w, camera.forward);
  const float cos2 = cos_theta * cos_theta;
  return 1.0f / (film_area(camera) * cos2 * cos2);
  // PLACEHOLDER
  // report_unfinished_task("stage6.camera.importance");
  // (void)camera, (void)w;
  // return 0.0f;
  // END TASK
}

float camera_direction_pdf(const Camera& camera, Vec3 w) {
  if (!project_to_film(camera, camera.position + w)) return 0.0f;
  const float cos_theta = glm::dot(w, camera.forward);
  return 1.0f / (film_area(camera) * cos_theta * cos_theta * cos_theta);
}

}  // namespace rt
