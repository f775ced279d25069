#include "experiments/sphere_precision.h"

#include "common/random.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rt {

FarSphereRays make_far_sphere_rays(float distance, int count, std::uint64_t seed) {
  FarSphereRays setup{Sphere{Vec3(0, 0, distance), 1.0f}, {}};
  setup.rays.reserve(size_t(count));
  Rng rng(seed, std::uint64_t(distance), 0);
  for (int i = 0; i < count; ++i) {
    // Uniform in the disk (polar warp r = R sqrt(u), so area, not radius, is uniform).
    const float radius = 1.1f * std::sqrt(rng.uniform()), angle = 2.0f * kPi * rng.uniform();
    const Vec3 target(radius * std::cos(angle), radius * std::sin(angle), distance);
    setup.rays.push_back(Ray{Vec3(0), glm::normalize(target)});
  }
  return setup;
}

std::vector<std::optional<float>> far_sphere_answers(SphereIntersectFn intersect, const FarSphereRays& setup) {
  std::vector<std::optional<float>> answers;
  answers.reserve(setup.rays.size());
  for (const Ray& ray : setup.rays) answers.push_back(intersect(ray, setup.sphere, Interval::positive()));
  return answers;
}

SpherePrecision measure_sphere_precision(SphereIntersectFn intersect, const FarSphereRays& setup) {
  return measure_sphere_precision(setup, far_sphere_answers(intersect, setup));
}

SpherePrecision measure_sphere_precision(const FarSphereRays& setup, const std::vector<std::optional<float>>& answers) {
  using LD = long double;
  const LD distance = setup.sphere.center.z, r = setup.sphere.radius;
  // Rays that pass within 4 ulp(D) of the silhouette are too close to call in float.
  const LD band = 4.0L * distance * LD(std::numeric_limits<float>::epsilon());
  SpherePrecision result;
  int wrong = 0;
  std::vector<double> errors;
  for (size_t i = 0; i < setup.rays.size(); ++i) {
    const Ray& ray = setup.rays[i];
    // Reference: the perpendicular-distance form in long double, f = o - c = (0, 0, -D).
    const LD dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
    const LD a = dx * dx + dy * dy + dz * dz, b = -distance * dz;
    const LD px = -(b / a) * dx, py = -(b / a) * dy, pz = -distance - (b / a) * dz;
    const LD rho2 = px * px + py * py + pz * pz;  // squared distance from the centre to the line
    if (std::abs(std::sqrt(rho2) - r) < band) continue;
    ++result.rays_counted;
    const bool reference_hit = rho2 < r * r;
    const std::optional<float> t = answers.at(i);
    if (t.has_value() != reference_hit) {
      ++wrong;
      continue;
    }
    if (!reference_hit) continue;
    const LD t_ref = (-b - std::sqrt(a * (r * r - rho2))) / a;
    const double error = double(std::abs(LD(*t) - t_ref));
    const float t_float = float(t_ref);
    const double ulp = double(std::nextafter(t_float, kInfinity) - t_float);
    errors.push_back(error / double(t_ref));
    result.worst_in_ulp_budget = std::max(result.worst_in_ulp_budget, error / (8.0 * ulp + 1e-6 * double(r)));
  }
  result.wrong_fraction = result.rays_counted ? double(wrong) / result.rays_counted : 0.0;
  if (!errors.empty()) {
    std::nth_element(errors.begin(), errors.begin() + long(errors.size() / 2), errors.end());
    result.median_relative_error = errors[errors.size() / 2];
    result.max_relative_error = *std::max_element(errors.begin(), errors.end());
  }
  return result;
}

}  // namespace rt
