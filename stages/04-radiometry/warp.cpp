#include "04-radiometry/warp.h"

#include "common/task.h"

namespace rt {

namespace {

// A unit vector from cos(theta) and phi about +z.
Vec3 from_cos_theta_phi(float cos_theta, float phi) {
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

}  // namespace

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

Vec2 sample_uniform_disk(Vec2 u) {
  // BEGIN TASK stage4.warp.concentric_disk
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return Vec2(0.0f);
  // The square [-1, 1]^2 is cut by its diagonals into four triangles; in each, the coordinate
  // with the larger magnitude is the radius and the other sweeps the angle over a quarter turn.
  float r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = 0.25f * kPi * (b / a);
  } else {
    r = b;
    phi = 0.5f * kPi - 0.25f * kPi * (a / b);
  }
  return r * Vec2(std::cos(phi), std::sin(phi));
  // PLACEHOLDER
  // report_unfinished_task("stage4.warp.concentric_disk");
  // (void)u;
  // return Vec2(0.0f);
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

float ggx_ndf(Vec3 m, float alpha) {
  if (m.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float d = (a2 - 1.0f) * m.z * m.z + 1.0f;
  return a2 / (kPi * d * d);
}

float ggx_lambda(Vec3 w, float alpha) {
  const float cos2 = w.z * w.z;
  if (cos2 == 0.0f) return kInfinity;  // grazing: fully masked
  const float tan2 = std::max(0.0f, 1.0f - cos2) / cos2;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

Vec3 sample_ggx_normal(Vec2 u, float alpha) {
  const float tan2 = alpha * alpha * u.x / (1.0f - u.x);
  return from_cos_theta_phi(1.0f / std::sqrt(1.0f + tan2), 2.0f * kPi * u.y);
}

Vec3 sample_ggx_visible_normal(Vec3 wo, Vec2 u, float alpha) {
  // BEGIN TASK stage4.warp.ggx_visible
  // 1. Stretch wo into the configuration where the microsurface is a hemisphere (alpha = 1).
  const Vec3 v = glm::normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));
  // 2. An orthonormal basis around v.
  const float len2 = v.x * v.x + v.y * v.y;
  const Vec3 t1 = len2 > 0.0f ? Vec3(-v.y, v.x, 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = glm::cross(v, t1);
  // 3. A point on the disk the hemisphere projects to along v: the near half-disk is seen whole,
  //    the far half foreshortened by v.z, hence the squeeze of the second coordinate.
  const Vec2 d = sample_uniform_disk(u);
  const float s = 0.5f * (1.0f + v.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - d.x * d.x)) + s * d.y;
  // 4. Lift it onto the hemisphere, then unstretch the normal.
  const Vec3 n = d.x * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - p2 * p2)) * v;
  return glm::normalize(Vec3(alpha * n.x, alpha * n.y, std::max(0.0f, n.z)));
  // PLACEHOLDER
  // report_unfinished_task("stage4.warp.ggx_visible");
  // (void)wo, (void)u, (void)alpha;
  // return Vec3(0.0f, 0.0f, 1.0f);
  // END TASK
}

float ggx_visible_normal_pdf(Vec3 wo, Vec3 m, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  return ggx_smith_g1(wo, alpha) * std::max(0.0f, glm::dot(wo, m)) * ggx_ndf(m, alpha) / wo.z;
}

}  // namespace rt
