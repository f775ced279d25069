#include "04-radiometry/microfacet.h"

#include "04-radiometry/warp.h"
#include "common/task.h"

namespace rt {

Color fresnel_schlick_f0(Color f0, float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (Color(1.0f) - f0) * (m2 * m2 * m);
}

Color MicrofacetBrdf::eval(Vec3 wi, Vec3 wo) const {
  // BEGIN TASK stage4.brdf.microfacet
  if (wi.z <= 0.0f || wo.z <= 0.0f) return Color(0.0f);
  const Vec3 half = wi + wo;
  if (glm::dot(half, half) == 0.0f) return Color(0.0f);
  const Vec3 h = glm::normalize(half);
  const float g2 = 1.0f / (1.0f + ggx_lambda(wi, alpha) + ggx_lambda(wo, alpha));
  return fresnel_schlick_f0(f0, glm::dot(wi, h)) * (ggx_ndf(h, alpha) * g2 / (4.0f * wi.z * wo.z));
  // PLACEHOLDER
  // report_unfinished_task("stage4.brdf.microfacet");
  // (void)wi, (void)wo;
  // return Color(0.0f);
  // END TASK
}

std::optional<BrdfSample> MicrofacetBrdf::sample(Vec3 wo, Vec2 u, float) const {
  if (wo.z <= 0.0f) return std::nullopt;
  const Vec3 m = sample_ggx_visible_normal(wo, u, alpha);
  const float wo_dot_m = glm::dot(wo, m);
  if (!(wo_dot_m > 0.0f)) return std::nullopt;
  const Vec3 wi = 2.0f * wo_dot_m * m - wo;
  if (wi.z <= 0.0f) return std::nullopt;  // reflected below the surface: masked, a wasted sample
  const float p = pdf(wi, wo);
  if (!(p > 0.0f)) return std::nullopt;
  return BrdfSample{wi, eval(wi, wo) * wi.z / p, p, false};
}

float MicrofacetBrdf::pdf(Vec3 wi, Vec3 wo) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  const Vec3 half = wi + wo;
  if (glm::dot(half, half) == 0.0f) return 0.0f;
  const Vec3 h = glm::normalize(half);
  return ggx_visible_normal_pdf(wo, h, alpha) / (4.0f * glm::dot(wo, h));
}

}  // namespace rt
