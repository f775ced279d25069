// Stage 4: an environment light, radiance arriving from infinitely far away in every direction:
// L_env(w), looked up in a latitude-longitude image (common/spherical.h: theta from +y, phi about it)
// turned by a rotation about +y, or a constant. A ray that leaves the scene sees L_env(d).
//
// Importance sampling it (the method of Pharr, Jakob & Humphreys, "Physically Based Rendering", 4th
// ed., section 12.5.3): the image is a table f(s, t) over the unit square, s = u = phi / 2 pi across
// and t = theta / pi down, and the 2D piecewise-constant density of 04-radiometry/piecewise_constant.h
// picks (s, t) in proportion to it. But the map squeezes the sphere: a texel near a pole covers a
// sliver of solid angle. With theta = pi t and phi = 2 pi s, dw = sin(theta) dtheta dphi =
// 2 pi^2 sin(theta) ds dt, so a density p(s, t) on the square is, per unit solid angle,
//     p(w) = p(s, t) / (2 pi^2 sin(theta)).
// Tabulating f = luminance(texel) x sin(theta of the row's centre) makes p(w) follow the
// radiance itself, not the texel count: without the sin, the poles' many small texels would draw
// samples out of proportion to the light they send. A constant environment needs no table: it is
// sampled uniformly over the sphere, p(w) = 1 / (4 pi), which makes L / p the same for every sample.
#pragma once

#include "04-radiometry/piecewise_constant.h"
#include "common/scene.h"

#include <memory>
#include <optional>

namespace rt {

enum class EnvironmentSampling {
  importance,  // by the 2D table of luminance x sin(theta), the default
  uniform,     // uniformly over the sphere, p = 1 / (4 pi): blind to where the light is
};

struct EnvironmentSample {
  Vec3 wi;         // world direction towards the environment
  float pdf;       // per unit solid angle
  Color radiance;  // L_env(wi)
};

class EnvironmentLight {
 public:
  explicit EnvironmentLight(const Environment& environment,
                            EnvironmentSampling strategy = EnvironmentSampling::importance);

  // L_env arriving from world direction `w` (unit): the texel that direction falls in, times the
  // scale (nearest lookup, so that radiance and density are constant over the same texels).
  Color radiance(Vec3 w) const;
  // Task stage4.env.sample. A direction by the 2D table (or uniformly on the sphere, for a constant
  // environment or by choice), with its solid-angle density; nullopt where that density is not
  // finite (a pole).
  std::optional<EnvironmentSample> sample(Vec2 u) const;
  // Task stage4.env.pdf. The density sample() draws world direction `w` with.
  float pdf(Vec3 w) const;
  // Luminance of the flux it sends through a disk of radius r facing it from every side,
  // pi r^2 integral L dw, with r the scene's bounding radius: its weight against the area emitters
  // when a light is chosen by power (pbrt's estimate of an infinite light's power).
  float power(float scene_radius) const;

  bool constant() const { return !image_; }
  // Whether sample() draws from the table (an image, importance sampled).
  bool uses_table() const { return distribution_.has_value(); }

 private:
  Vec3 to_local(Vec3 w) const;   // world -> the map's frame (undoes the rotation)
  Vec3 to_world(Vec3 d) const;
  Color texel(Vec2 st) const;  // (s, t) in [0, 1)^2, t down the image

  std::shared_ptr<const Image> image_;
  Color scale_;
  float cos_rotation_, sin_rotation_;
  std::optional<PiecewiseConstant2D> distribution_;  // the table, for an image
};

}  // namespace rt
