// Stage 1: the experiment behind the stable sphere formula (Haines et al., Ray Tracing Gems ch. 7):
// a unit sphere at distance D from the camera, rays from the origin aimed uniformly at a disk of
// radius 1.1 around its centre (about 83% of them hit), each float answer compared with a long
// double answer for the SAME float ray. Used by tests/stage1/sphere_test.cpp and by the chart
// program benchmarks/sphere_precision.cpp.
#pragma once

#include "common/interval.h"
#include "common/ray.h"
#include "common/scene.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace rt {

using SphereIntersectFn = std::optional<float> (*)(const Ray&, const Sphere&, Interval);

struct FarSphereRays {
  Sphere sphere;
  std::vector<Ray> rays;
};

FarSphereRays make_far_sphere_rays(float distance, int count, std::uint64_t seed);

struct SpherePrecision {
  int rays_counted = 0;            // rays not within 4 ulp(D) of the silhouette (too close to call)
  double wrong_fraction = 0.0;     // hit/miss answers that disagree with the reference
  double median_relative_error = 0.0;  // |t - t_ref| / t_ref over the agreed hits
  double max_relative_error = 0.0;
  double worst_in_ulp_budget = 0.0;    // max |t - t_ref| / (8 ulp(t_ref) + 1e-6 r)
};

SpherePrecision measure_sphere_precision(SphereIntersectFn intersect, const FarSphereRays& setup);
// The same in two halves: the formula's answers for setup.rays, in order (what a graded test
// records), and their measure.
std::vector<std::optional<float>> far_sphere_answers(SphereIntersectFn intersect, const FarSphereRays& setup);
SpherePrecision measure_sphere_precision(const FarSphereRays& setup, const std::vector<std::optional<float>>& answers);

}  // namespace rt
