// What an intersection reports, the same record for every shape in every stage.
#pragma once

#include "common/math.h"
#include "common/ray.h"

namespace rt {

struct Hit {
  float t = kInfinity;
  Vec3 point{0.0f};
  // Unit normal on the side the ray came from (opposite the ray), so shading never has to ask
  // which side it is on; front_face records whether that is the outward side.
  Vec3 normal{0.0f};
  // The normal shading uses: the geometric normal, or one interpolated from a mesh's vertex
  // normals (stage 2), always turned to the same side as `normal`.
  Vec3 shading_normal{0.0f};
  // Bound on the rounding error of `point`, per coordinate: the true surface point lies in the box
  // point +- point_error. Stage 2 fills it in and offsets secondary rays by it; zero means unknown.
  Vec3 point_error{0.0f};
  // Texture coordinates of the point (common/scene.h, ImageTexture, says which way they run):
  // interpolated from a mesh's corners, a sphere's (theta, phi), a plane's or disk's own frame.
  Vec2 uv{0.0f};
  bool front_face = true;
  int material = -1;
  int primitive = -1;  // index of the shape in its scene: how a hit finds its emitter (emitter_index)
  int triangle = -1;   // which triangle of a mesh shape, -1 for other shapes

  // The front-face rule, in one place: the ray hits the front (outward) side when it travels
  // against the outward normal.
  void set_face_normal(const Ray& ray, Vec3 outward_normal) {
    front_face = glm::dot(ray.direction, outward_normal) < 0.0f;
    // Both fields from one value in registers: copying `normal` into `shading_normal` would read
    // back, at once, a vector just written in pieces, which stalls (a failed store-to-load
    // forward; docs/stage5.md, the speed ladder).
    const Vec3 facing = front_face ? outward_normal : -outward_normal;
    normal = facing;
    shading_normal = facing;
  }
};

// The one place a hit record is filled: every shape of every stage reports its hit through here.
// `point_error` bounds the rounding error of `point` per coordinate (zero: unknown, stage 1).
inline Hit make_hit(const Ray& ray, float t, Vec3 point, Vec3 point_error, Vec3 outward_normal, int material,
                    int shape) {
  Hit hit;
  hit.t = t;
  hit.point = point;
  hit.point_error = point_error;
  hit.set_face_normal(ray, outward_normal);
  hit.material = material;
  hit.primitive = shape;
  return hit;
}

}  // namespace rt
