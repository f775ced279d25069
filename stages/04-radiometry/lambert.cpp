#include "04-radiometry/lambert.h"

#include "04-radiometry/warp.h"
#include "common/task.h"

namespace rt {

Color LambertBrdf::eval(Vec3 wo, Vec3 wi) const {
  // BEGIN TASK stage4.brdf.lambert
  if (wi.z <= 0.0f || wo.z <= 0.0f) return Color(0.0f);
  return albedo * kInvPi;
  // PLACEHOLDER
  // report_unfinished_task("stage4.brdf.lambert");
  // (void)wi, (void)wo;
  // return Color(0.0f);
  // END TASK
}

std::optional<BsdfSample> LambertBrdf::sample(Vec3 wo, Vec2 u, float) const {
  if (wo.z <= 0.0f) return std::nullopt;
  const Vec3 wi = sample_cosine_hemisphere(u);
  if (wi.z <= 0.0f) return std::nullopt;
  return BsdfSample{wi, albedo, cosine_hemisphere_pdf(wi), false};
}

float LambertBrdf::pdf(Vec3 wo, Vec3 wi) const { return wo.z > 0.0f ? cosine_hemisphere_pdf(wi) : 0.0f; }

}  // namespace rt
