#include "04-radiometry/ggx.h"

#include "04-radiometry/warp.h"
#include "common/task.h"

namespace rt {

float GgxDistribution::d(Vec3 m) const {
  if (m.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float denominator = (a2 - 1.0f) * m.z * m.z + 1.0f;
  return a2 / (kPi * denominator * denominator);
}

float GgxDistribution::lambda(Vec3 w) const {
  const float cos2 = w.z * w.z;
  if (cos2 == 0.0f) return kInfinity;  // grazing: fully masked
  const float tan2 = std::max(0.0f, 1.0f - cos2) / cos2;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

Vec3 GgxDistribution::sample_normal(Vec2 u) const {
  const float tan2 = alpha * alpha * u.x / (1.0f - u.x);
  return from_cos_theta_phi(1.0f / std::sqrt(1.0f + tan2), 2.0f * kPi * u.y);
}

Vec3 GgxDistribution::sample_visible_normal(Vec3 wo, Vec2 u) const {
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
  // (void)wo, (void)u;
  // return Vec3(0.0f, 0.0f, 1.0f);
  // END TASK
}

float GgxDistribution::visible_normal_pdf(Vec3 wo, Vec3 m) const {
  if (wo.z <= 0.0f) return 0.0f;
  return g1(wo) * std::max(0.0f, glm::dot(wo, m)) * d(m) / wo.z;
}

}  // namespace rt
