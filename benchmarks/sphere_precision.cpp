// Writes the CSV behind docs/charts/stage1-sphere-precision.png: for a unit sphere at distance D
// (2 to 1e6 radii), the textbook and the stable ray-sphere formulas' wrong hit/miss fraction and
// relative error in t against long double, next to their cost in ns per call, all from one run.
//   usage: sphere_precision [OUT.csv]        (stdout without an argument)
#include "01-ray-casting/sphere_intersection.h"
#include "experiments/sphere_precision.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace {

using namespace rt;

// Mean ns per call over the same rays, best of 5 passes (the least disturbed by other work).
double nanoseconds_per_call(SphereIntersectFn intersect, const FarSphereRays& setup) {
  double best = 1e30;
  for (int pass = 0; pass < 5; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    for (const Ray& ray : setup.rays)
      benchmark::DoNotOptimize(intersect(ray, setup.sphere, Interval::positive()));
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, ns / double(setup.rays.size()));
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  std::FILE* out = argc > 1 ? std::fopen(argv[1], "w") : stdout;
  if (!out) {
    std::fprintf(stderr, "sphere_precision: cannot write %s\n", argv[1]);
    return 1;
  }
  struct Formula {
    const char* name;
    SphereIntersectFn fn;
  };
  const Formula formulas[] = {{"textbook", intersect_sphere_textbook}, {"stable", intersect_sphere_stable}};
  std::fprintf(out, "distance_over_radius,formula,rays,wrong_fraction,median_relative_error,"
                    "max_relative_error,ns_per_call\n");
  // D = 10^(step / 2) = 3.16, 10, ..., 1e6, and D = 2 in place of 1: at D = 1 the camera would
  // sit on the sphere itself.
  for (int step = 0; step <= 12; ++step) {
    const float distance = std::max(std::pow(10.0f, 0.5f * float(step)), 2.0f);
    const FarSphereRays setup = make_far_sphere_rays(distance, 100'000, 1234);
    for (const Formula& f : formulas) {
      const SpherePrecision p = measure_sphere_precision(f.fn, setup);
      std::fprintf(out, "%g,%s,%d,%.6g,%.6g,%.6g,%.3f\n", double(setup.sphere.center.z), f.name,
                   p.rays_counted, p.wrong_fraction, p.median_relative_error, p.max_relative_error,
                   nanoseconds_per_call(f.fn, setup));
    }
  }
  if (out != stdout) std::fclose(out);
  return 0;
}
