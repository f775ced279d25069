#include "common/transform.h"

#include <glm/gtc/matrix_transform.hpp>

namespace rt {

Transform Transform::from_scale_rotate_translate(Vec3 scale, Vec3 rotate_degrees, Vec3 translate) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
  m = glm::rotate(m, radians(rotate_degrees.z), Vec3(0, 0, 1));
  m = glm::rotate(m, radians(rotate_degrees.y), Vec3(0, 1, 0));
  m = glm::rotate(m, radians(rotate_degrees.x), Vec3(1, 0, 0));
  m = glm::scale(m, scale);
  return Transform{m};
}

}  // namespace rt
