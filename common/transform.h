// Placing a mesh in the world: scale, then rotate, then translate (the order a scene file's
// "transform" block is read in, docs/scene-format.md). Points go through the full affine matrix;
// what happens to normals is a stage-2 lesson (stages/02-whitted/mesh_instance.h).
#pragma once

#include "common/math.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

namespace rt {

struct Transform {
  glm::mat4 matrix{1.0f};  // column vectors: p_world = matrix * (p, 1)

  // M = T * Rz * Ry * Rx * S: scale first, then rotate about x, y and z (degrees, right-handed),
  // then translate.
  static Transform from_scale_rotate_translate(Vec3 scale, Vec3 rotate_degrees, Vec3 translate);

  Vec3 point(Vec3 p) const { return Vec3(matrix * glm::vec4(p, 1.0f)); }
  // The upper-left 3x3 block: how the transform acts on directions and tangent vectors.
  glm::mat3 linear() const { return glm::mat3(matrix); }
};

}  // namespace rt
