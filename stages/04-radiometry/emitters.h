// Stage 4: area emitters, shapes whose material has an emitted radiance Le. Each emits from its
// front side only (a triangle's front is (v1 - v0) x (v2 - v0), a disk's its normal, a sphere's its
// outside) as a Lambertian emitter: the same Le in every direction of that hemisphere.
//
// Light sampling picks a point y on the emitter and returns the direction wi from the shading
// point x to it, with the density of wi per unit SOLID ANGLE seen from x: uniform area sampling
// has p_A = 1 / A, and p_w = p_A |x - y|^2 / |cos(theta_y)| (04-radiometry/radiometry.h). A sphere
// can instead be sampled by the cone of directions it subtends (uniform in solid angle, every
// sample on the visible side), which wastes nothing where area sampling wastes the far half.
#pragma once

#include "04-radiometry/bsdf_sample.h"

#include <optional>
#include <variant>

namespace rt {

struct EmitterSample {
  Vec3 point;      // y, on the emitter
  Vec3 wi;         // unit direction from the shading point x towards y
  float distance;  // |y - x|
  float pdf;       // density of wi per unit solid angle
};

struct TriangleEmitter {
  Vec3 v0, v1, v2;

  float area() const;
  Vec3 normal() const;  // unit, the emitting side
  // Task stage4.light.triangle: uniform over the area (stage4.warp.triangle), converted to
  // solid angle.
  EmitterSample sample(Vec3 x, Vec2 u) const;
  // The solid-angle density sample() gives the direction from x to the point y on the triangle.
  float pdf(Vec3 x, Vec3 y) const;
};

struct DiskEmitter {
  Vec3 center, normal;
  float radius;

  float area() const { return kPi * radius * radius; }
  EmitterSample sample(Vec3 x, Vec2 u) const;  // uniform over the area (stage4.warp.concentric_disk)
  float pdf(Vec3 x, Vec3 y) const;
};

enum class RectangleSampling {
  area,         // uniform over the area, the lecture's method: p_w varies with distance and tilt
  solid_angle,  // uniform over the solid angle it subtends (04-radiometry/spherical_rectangle.h)
};

// A rectangle corner + s edge_u + t edge_v, (s, t) in [0, 1]^2, with perpendicular edges: a quad
// light such as the Cornell box's, as one emitter (its geometry in the BVH stays two triangles).
// Its front is edge_u x edge_v.
struct RectangleEmitter {
  RectangleEmitter(Vec3 corner, Vec3 edge_u, Vec3 edge_v, RectangleSampling strategy = RectangleSampling::area)
      : corner(corner), edge_u(edge_u), edge_v(edge_v), strategy(strategy), front(glm::cross(edge_u, edge_v)),
        unit_normal(glm::normalize(front)), inverse_area(1.0f / glm::length(front)) {}

  Vec3 corner, edge_u, edge_v;
  RectangleSampling strategy;
  // Computed once from the edges, not at every sample (a light is sampled at every vertex of every
  // path): the emitting side's normal scaled by the area, that normal, and 1 / area.
  Vec3 front, unit_normal;
  float inverse_area;

  float area() const { return glm::length(front); }
  Vec3 normal() const { return unit_normal; }
  // By solid angle where x sees the front and the rectangle subtends at least kMinSolidAngle;
  // otherwise by area. From behind, the rectangle emits nothing towards x: no sample (pdf 0).
  EmitterSample sample(Vec3 x, Vec2 u) const;
  float pdf(Vec3 x, Vec3 y) const;

  // Below this, far away or seen edge-on, the solid angle keeps fewer digits (its set-up is in
  // double, but x's coordinates in the rectangle's frame are rounded to float: measured, S is good
  // to 1e-6 sr, a relative 1e-4 here), and area sampling is as good anyway: the light is nearly a
  // point, whose 1/r^2 hardly varies over it.
  static constexpr float kMinSolidAngle = 0.01f;
};

enum class SphereSampling {
  area,  // uniform over the whole sphere, p_A = 1 / (4 pi r^2): half the samples land on the far side
  cone,  // uniform over the cone of directions the sphere subtends from x (from outside it)
};

struct SphereEmitter {
  Vec3 center;
  float radius;
  SphereSampling strategy = SphereSampling::cone;

  float area() const { return 4.0f * kPi * radius * radius; }
  // Task stage4.light.sphere_cone (the cone branch): with sin(theta_max) = r / |c - x|, a direction
  // uniform in the cone about c - x (stage4.warp.cone), and y the nearer point where it meets
  // the sphere. From inside the sphere, area sampling.
  EmitterSample sample(Vec3 x, Vec2 u) const;
  float pdf(Vec3 x, Vec3 y) const;
  Vec3 normal_at(Vec3 y) const { return (y - center) / radius; }
};

// One emitting surface and its radiance; `shape` is its index in the scene file.
struct AreaEmitter {
  std::variant<TriangleEmitter, RectangleEmitter, DiskEmitter, SphereEmitter> geometry;
  Color radiance;
  int shape = -1;

  float area() const {
    return std::visit([](const auto& g) { return g.area(); }, geometry);
  }
  EmitterSample sample(Vec3 x, Vec2 u) const {
    return std::visit([&](const auto& g) { return g.sample(x, u); }, geometry);
  }
  float pdf(Vec3 x, Vec3 y) const {
    return std::visit([&](const auto& g) { return g.pdf(x, y); }, geometry);
  }
  // The unit normal of the emitting side at a point y on the emitter.
  Vec3 normal_at(Vec3 y) const;
  // Le leaving y towards x: the radiance on the front side, black behind.
  Color radiance_towards(Vec3 y, Vec3 x) const;
  // Luminance of the emitted flux, pi Le A: the weight for choosing among emitters.
  float power() const;
};

}  // namespace rt
