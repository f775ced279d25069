#include "04-radiometry/microfacet.h"

#include "02-whitted/optics.h"
#include "common/task.h"

namespace rt {

Color MicrofacetBrdf::eval(Vec3 wo, Vec3 wi) const {
  // BEGIN TASK stage4.brdf.microfacet
  if (wi.z <= 0.0f || wo.z <= 0.0f) return Color(0.0f);
  const Vec3 half = wo + wi;
  if (glm::dot(half, half) == 0.0f) return Color(0.0f);
  const Vec3 h = glm::normalize(half);
  return schlick(f0, glm::dot(wi, h)) * (ggx.d(h) * ggx.g2(wo, wi) / (4.0f * wi.z * wo.z));
  // PLACEHOLDER
  // report_unfinished_task("stage4.brdf.microfacet");
  // (void)wi, (void)wo;
  // return Color(0.0f);
  // END TASK
}

std::optional<BsdfSample> MicrofacetBrdf::sample(Vec3 wo, Vec2 u, float) const {
  if (wo.z <= 0.0f) return std::nullopt;
  const Vec3 m = ggx.sample_visible_normal(wo, u);
  const float wo_dot_m = glm::dot(wo, m);
  if (!(wo_dot_m > 0.0f)) return std::nullopt;
  const Vec3 wi = 2.0f * wo_dot_m * m - wo;
  if (wi.z <= 0.0f) return std::nullopt;  // reflected below the surface: masked, a wasted sample
  const float p = pdf(wo, wi);
  if (!(p > 0.0f)) return std::nullopt;
  return BsdfSample{wi, eval(wo, wi) * wi.z / p, p, false};
}

float MicrofacetBrdf::pdf(Vec3 wo, Vec3 wi) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  const Vec3 half = wo + wi;
  if (glm::dot(half, half) == 0.0f) return 0.0f;
  const Vec3 h = glm::normalize(half);
  return ggx.visible_normal_pdf(wo, h) / (4.0f * glm::dot(wo, h));
}

}  // namespace rt
