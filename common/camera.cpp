#include "common/camera.h"

#include <cmath>
#include <stdexcept>

namespace rt {

Camera::Camera(const CameraSpec& spec, int width_, int height_)
    : position(spec.position), width(width_), height(height_), aperture_radius(spec.aperture_radius) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("image size must be positive");
  if (!(spec.vfov_degrees > 0.0f && spec.vfov_degrees < 180.0f))
    throw std::invalid_argument("vertical field of view must be in (0, 180) degrees");
  if (!(spec.aperture_radius >= 0.0f && std::isfinite(spec.aperture_radius)))
    throw std::invalid_argument("aperture radius must be finite and at least 0");
  if (!(spec.focus_distance >= 0.0f && std::isfinite(spec.focus_distance)))
    throw std::invalid_argument("focus distance must be finite and at least 0");
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
  focus_distance = spec.focus_distance > 0.0f ? spec.focus_distance : glm::length(view);
}

}  // namespace rt
