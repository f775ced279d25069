// Stage 2: a ray prepared once for every triangle test it meets, and the choice among the tests.
#pragma once

#include "02-whitted/triangle_intersection.h"
#include "02-whitted/triangle_lanes.h"
#include "02-whitted/triangle_pack.h"

namespace rt {

// watertight_lanes: the watertight test with a triangle's corners in SIMD lanes (triangle_lanes.h),
// the watertight test's answers bit for bit, in fewer instructions.
enum class TriangleMethod { moller_trumbore, watertight, watertight_lanes };

// A ray with what each test needs, prepared once.
struct TriangleRay {
  Ray ray;
  WatertightRay watertight;
  LanesRay lanes;
  explicit TriangleRay(const Ray& r) : ray(r), watertight(r), lanes(watertight) {}
};

std::optional<TriangleHit> intersect_triangle(TriangleMethod method, const TriangleRay& ray, Vec3 v0, Vec3 v1,
                                              Vec3 v2, Interval range);
inline std::optional<TriangleHit> intersect_triangle(TriangleMethod method, const Ray& ray, Vec3 v0, Vec3 v1,
                                                     Vec3 v2, Interval range) {
  return intersect_triangle(method, TriangleRay(ray), v0, v1, v2, range);
}

}  // namespace rt
