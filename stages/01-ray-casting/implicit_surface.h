// Stage 1: a general implicit surface f(p) = 0, intersected by root finding along the ray,
// g(t) = f(o + t d) = 0. The torus is the worked example: its quartic has no stable closed form
// worth teaching, but its distance function is one line.
#pragma once

#include "common/interval.h"
#include "common/ray.h"
#include "common/scene.h"

#include <optional>

namespace rt {

// A surface given by a signed distance BOUND: f < 0 inside, f > 0 outside, and |f(p)| is at most
// the distance from p to the surface (f is 1-Lipschitz). That bound is what makes sphere tracing
// safe: a step of |f| can never jump over the surface (Hart, "Sphere Tracing", The Visual
// Computer 12(10), 1996).
class ImplicitSurface {
 public:
  virtual ~ImplicitSurface() = default;
  virtual float distance(Vec3 p) const = 0;
  // The true gradient of f (Newton's method divides by grad f . d, so a scaled stand-in would
  // make it overshoot); it points outward, and for an exact distance it has unit length.
  virtual Vec3 gradient(Vec3 p) const = 0;
  virtual Sphere bounding_sphere() const = 0;
};

class TorusSurface final : public ImplicitSurface {
 public:
  explicit TorusSurface(const Torus& torus) : torus_(torus) {}
  // Distance to the core circle of radius R, minus the tube radius r:
  //   f(p) = sqrt((rho - R)^2 + h^2) - r,
  // with h the height of p along the axis and rho its distance from the axis. Exact, so 1-Lipschitz.
  float distance(Vec3 p) const override;
  Vec3 gradient(Vec3 p) const override;
  Sphere bounding_sphere() const override {
    return Sphere{torus_.center, torus_.major_radius + torus_.minor_radius};
  }

 private:
  Torus torus_;
};

struct ImplicitHit {
  float t;
  int steps;  // sphere-tracing steps taken, for the handout's discussion of grazing rays
};

// Task stage1.implicit.intersect. The nearest root of g(t) = f(o + t d) strictly inside `range`:
//  1. clip the range to the bounding sphere (stable sphere intersection), so rays that miss cost
//     nothing and marching starts close to the surface;
//  2. sphere-trace: t += |g(t)|. From outside this never crosses the surface, from inside it
//     never leaves it, so the first |g| below the tolerance is the nearest root;
//  3. if a step does change the sign of g (rounding next to the surface; or an f that somewhere
//     overestimates the distance, which breaks the bound), bisect the bracket;
//  4. polish with Newton steps, t -= g / g', g' = grad f . d, kept while they shrink |g|.
// A ray that grazes the surface makes sphere tracing crawl: a root found at step n counts only for
// n < kMaxSphereTracingSteps (ImplicitHit::steps = n; the first |g| is step 0), so a ray that
// needs kMaxSphereTracingSteps steps or more is a miss.
std::optional<ImplicitHit> intersect_implicit(const ImplicitSurface& surface, const Ray& ray,
                                              Interval range);

inline constexpr int kMaxSphereTracingSteps = 512;

}  // namespace rt
