// Stage 2: self-intersection. A computed hit point is rounded, so it lies a little above or below
// the true surface. A secondary ray started there can hit the very surface it leaves (shadow acne,
// black speckles) or, offset too far, start beyond a nearby surface (light leaking through
// contacts). Three ways to pick the start point, compared in docs/stage2.md:
//  - fixed: p + epsilon n. One epsilon cannot suit every scene scale.
//  - error_bound: carry a bound on the point's rounding error with every hit, and move out of that
//    error box along the normal (Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed.,
//    section 6.8.6). Scale-free by construction.
//  - integer_ulp: move each coordinate a fixed number of ulps along the normal (Waechter & Binder,
//    "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6, 2019).
#pragma once

#include "common/hit.h"
#include "common/interval.h"
#include "common/scene.h"

namespace rt {

// gamma_n = n u / (1 - n u), u = 2^-24 the unit roundoff of float: a bound on the relative error
// of n chained float operations (Higham, Accuracy and Stability of Numerical Algorithms, 2002;
// PBR 4th ed. eq. 6.33).
constexpr float gamma_bound(int n) {
  constexpr float u = 0x1p-24f;
  return float(n) * u / (1.0f - float(n) * u);
}

// Where a hit really is: a point computed on the surface, and a bound on its error per coordinate.
struct SurfacePoint {
  Vec3 point;
  Vec3 error;
};

// A point on a triangle from its barycentrics, p = b0 v0 + b1 v1 + b2 v2, which is accurate to
// gamma_7 (|b0 v0| + |b1 v1| + |b2 v2|) (PBR 4th ed. section 6.8.5): far better than o + t d,
// whose error grows with the ray's length.
SurfacePoint triangle_point(Vec3 b, Vec3 v0, Vec3 v1, Vec3 v2);
// o + t d projected back onto the sphere, c + r (p - c) / |p - c|: error gamma_5 |p - c| from the
// projection plus one rounding for adding c.
SurfacePoint sphere_point(Vec3 p, const Sphere& sphere);
// o + t d projected back onto the plane, p - ((p - p0).n) n.
SurfacePoint plane_point(Vec3 p, const Plane& plane);

enum class OffsetMethod { error_bound, integer_ulp, fixed };

struct OffsetPolicy {
  OffsetMethod method = OffsetMethod::error_bound;
  float epsilon = 1e-4f;  // the distance along the normal, for OffsetMethod::fixed only
};

// Task stage2.offset.error_bound (the error_bound branch). The start of a ray leaving `hit` in
// `direction`, on the side of the surface the direction points to. For error_bound: the error box
// reaches d = |n_x| e_x + |n_y| e_y + |n_z| e_z along the normal, so start at p +- d n and round
// each coordinate one float further away, so that rounding the sum cannot undo the offset.
Vec3 offset_ray_origin(const Hit& hit, Vec3 direction, const OffsetPolicy& policy);

// A ray leaving the surface at `hit` in a unit `direction`.
Ray spawn_ray(const Hit& hit, Vec3 direction, const OffsetPolicy& policy);

// A shadow ray from `hit` towards `target` (a point light), with the range that stops just short
// of the target, so that a light sitting on a surface is not shadowed by that surface.
struct ShadowRay {
  Ray ray;
  Interval range;
};
ShadowRay spawn_shadow_ray(const Hit& hit, Vec3 target, const OffsetPolicy& policy);

// The shadow ray ends (1 - kShadowEpsilon) of the way to the light, a relative (scale-free) margin.
inline constexpr float kShadowEpsilon = 1e-4f;

}  // namespace rt
