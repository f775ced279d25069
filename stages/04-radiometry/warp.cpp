#include "04-radiometry/warp.h"

#include "common/task.h"

namespace rt {

Vec3 from_cos_theta_phi(float cos_theta, float phi) {
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

Vec3 sample_uniform_hemisphere(Vec2 u) { return from_cos_theta_phi(u.x, 2.0f * kPi * u.y); }

Vec3 sample_uniform_sphere(Vec2 u) { return from_cos_theta_phi(1.0f - 2.0f * u.x, 2.0f * kPi * u.y); }

Vec3 sample_cosine_hemisphere(Vec2 u) {
  // BEGIN TASK stage4.warp.cosine_hemisphere
  const Vec2 d = sample_uniform_disk(u);
  return Vec3(d.x, d.y, std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y)));
  // PLACEHOLDER
  // report_unfinished_task("stage4.warp.cosine_hemisphere");
  // (void)u;
  // return Vec3(0.0f, 0.0f, 1.0f);
  // END TASK
}

Vec3 sample_uniform_cone(Vec2 u, float cos_theta_max) {
  // BEGIN TASK stage4.warp.cone
  // (1 - u0) + u0 cos_theta_max rather than 1 - u0 (1 - cos_theta_max): exact at both ends.
  return from_cos_theta_phi((1.0f - u.x) + u.x * cos_theta_max, 2.0f * kPi * u.y);
  // PLACEHOLDER
  // report_unfinished_task("stage4.warp.cone");
  // (void)u, (void)cos_theta_max;
  // return Vec3(0.0f, 0.0f, 1.0f);
  // END TASK
}

Vec3 sample_uniform_triangle(Vec2 u) {
  // BEGIN TASK stage4.warp.triangle
  const float s = std::sqrt(u.x);
  const float b0 = 1.0f - s, b1 = u.y * s;
  return Vec3(b0, b1, std::max(0.0f, 1.0f - b0 - b1));
  // PLACEHOLDER
  // report_unfinished_task("stage4.warp.triangle");
  // (void)u;
  // return Vec3(1.0f / 3.0f);
  // END TASK
}

namespace {

// u1 = phi / (2 pi), phi the azimuth of w in [0, 2 pi).
float azimuth_fraction(float x, float y) {
  const float phi = std::atan2(y, x);
  return (phi < 0.0f ? phi + 2.0f * kPi : phi) * (0.5f * kInvPi);
}

}  // namespace

Vec2 invert_uniform_hemisphere(Vec3 w) { return Vec2(w.z, azimuth_fraction(w.x, w.y)); }

Vec2 invert_uniform_sphere(Vec3 w) { return Vec2(0.5f * (1.0f - w.z), azimuth_fraction(w.x, w.y)); }

Vec2 invert_cosine_hemisphere(Vec3 w) { return invert_uniform_disk(Vec2(w.x, w.y)); }

Vec2 invert_uniform_cone(Vec3 w, float cos_theta_max) {
  return Vec2((1.0f - w.z) / (1.0f - cos_theta_max), azimuth_fraction(w.x, w.y));
}

Vec2 invert_uniform_triangle(Vec3 b) {
  const float s = 1.0f - b.x;  // sqrt(u0)
  return Vec2(s * s, s > 0.0f ? b.y / s : 0.0f);
}

}  // namespace rt
