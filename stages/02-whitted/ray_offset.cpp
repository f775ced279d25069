#include "02-whitted/ray_offset.h"

#include "common/task.h"

#include <bit>
#include <cstdint>

namespace rt {

SurfacePoint triangle_point(Vec3 b, Vec3 v0, Vec3 v1, Vec3 v2) {
  const Vec3 p = b.x * v0 + b.y * v1 + b.z * v2;
  const Vec3 magnitude = glm::abs(b.x * v0) + glm::abs(b.y * v1) + glm::abs(b.z * v2);
  return {p, gamma_bound(7) * magnitude};
}

SurfacePoint sphere_point(Vec3 p, const Sphere& sphere) {
  Vec3 local = p - sphere.center;
  local *= sphere.radius / glm::length(local);
  const Vec3 point = sphere.center + local;
  return {point, gamma_bound(5) * glm::abs(local) + gamma_bound(1) * glm::abs(point)};
}

SurfacePoint plane_point(Vec3 p, const Plane& plane) {
  // s = (p - p0).n: a difference and a 3-term dot product, error within
  // gamma_5 sum_j (|p_j| + |p0_j|) |n_j|; each coordinate of s n then moves by |n_i| times that.
  const Vec3 n = plane.normal;
  const float s = glm::dot(p - plane.point, n);
  const Vec3 point = p - s * n;
  const float s_error = gamma_bound(5) * glm::dot(glm::abs(p) + glm::abs(plane.point), glm::abs(n));
  return {point, gamma_bound(2) * (glm::abs(point) + glm::abs(s * n)) + s_error * glm::abs(n)};
}

namespace {

// Waechter & Binder's constants (Ray Tracing Gems ch. 6, listing 6-1): 256 ulps along the normal,
// and a plain offset of 1/65536 for coordinates within 1/32 of zero, where ulps get too small.
constexpr float kUlpOrigin = 1.0f / 32.0f;
constexpr float kUlpFloatScale = 1.0f / 65536.0f;
constexpr float kUlpIntScale = 256.0f;

Vec3 integer_ulp_offset(Vec3 p, Vec3 n) {
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(p[i]) < kUlpOrigin) {
      out[i] = p[i] + kUlpFloatScale * n[i];
      continue;
    }
    // Adding k to the bit pattern of a positive float moves it k ulps up; the sign of p decides
    // whether "up" in bits is up or down in value.
    const auto ulps = std::int32_t(kUlpIntScale * n[i]);
    const auto bits = std::bit_cast<std::int32_t>(p[i]);
    out[i] = std::bit_cast<float>(bits + (p[i] < 0.0f ? -ulps : ulps));
  }
  return out;
}

}  // namespace

Vec3 offset_ray_origin(const Hit& hit, Vec3 direction, const OffsetPolicy& policy) {
  // The geometric normal, turned to the side the new ray leaves by (a refracted ray leaves
  // through the back).
  const Vec3 n = glm::dot(direction, hit.normal) < 0.0f ? -hit.normal : hit.normal;
  switch (policy.method) {
    case OffsetMethod::fixed:
      return hit.point + policy.epsilon * n;
    case OffsetMethod::integer_ulp:
      return integer_ulp_offset(hit.point, n);
    case OffsetMethod::error_bound: {
      // BEGIN TASK stage2.offset.error_bound
      const float d = glm::dot(glm::abs(n), hit.point_error);
      const Vec3 offset = d * n;
      Vec3 origin = hit.point + offset;
      for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0.0f) origin[i] = next_float_up(origin[i]);
        else if (offset[i] < 0.0f) origin[i] = next_float_down(origin[i]);
      }
      return origin;
      // PLACEHOLDER
      // report_unfinished_task("stage2.offset.error_bound");
      // return hit.point + policy.epsilon * n;  // the fixed epsilon until this is done
      // END TASK
    }
  }
  return hit.point;
}

Ray spawn_ray(const Hit& hit, Vec3 direction, const OffsetPolicy& policy) {
  return Ray{offset_ray_origin(hit, direction, policy), direction};
}

ShadowRay spawn_shadow_ray(const Hit& hit, Vec3 target, const OffsetPolicy& policy) {
  const Vec3 origin = offset_ray_origin(hit, target - hit.point, policy);
  const Vec3 span = target - origin;
  const float distance = glm::length(span);
  return ShadowRay{Ray{origin, span / distance}, Interval{0.0f, distance * (1.0f - kShadowEpsilon)}};
}

}  // namespace rt
