#include "common/camera.h"

#include <stdexcept>

namespace rt {

PinholeCamera::PinholeCamera(const CameraSpec& spec, int width_, int height_)
    : position(spec.position), width(width_), height(height_) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("image size must be positive");
  if (!(spec.vfov_degrees > 0.0f && spec.vfov_degrees < 180.0f))
    throw std::invalid_argument("vertical field of view must be in (0, 180) degrees");
  const Vec3 view = spec.look_at - spec.position;
  if (!(glm::length(view) > 0.0f)) throw std::invalid_argument("look_at equals position");
  forward = glm::normalize(view);
  const Vec3 side = glm::cross(forward, spec.up);
  if (!(glm::length(side) > 1e-6f * glm::length(spec.up)))
    throw std::invalid_argument("up is parallel to the view direction");
  right = glm::normalize(side);
  up = glm::cross(right, forward);
  tan_half_vfov = std::tan(0.5f * radians(spec.vfov_degrees));
  aspect = float(width) / float(height);
}

}  // namespace rt
