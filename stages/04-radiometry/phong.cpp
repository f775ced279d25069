#include "04-radiometry/phong.h"

#include "04-radiometry/warp.h"
#include "common/frame.h"
#include "common/task.h"

namespace rt {

namespace {

// cos(alpha), alpha the angle between wi and the mirror direction of wo: symmetric in the two.
float lobe_cosine(Vec3 wo, Vec3 wi) { return std::max(0.0f, glm::dot(wi, mirror_local(wo))); }

}  // namespace

Color PhongBrdf::eval(Vec3 wo, Vec3 wi) const {
  // BEGIN TASK stage4.brdf.phong
  if (wi.z <= 0.0f || wo.z <= 0.0f) return Color(0.0f);
  const float lobe = (exponent + 2.0f) * 0.5f * kInvPi * std::pow(lobe_cosine(wo, wi), exponent);
  return diffuse * kInvPi + specular * lobe;
  // PLACEHOLDER
  // report_unfinished_task("stage4.brdf.phong");
  // (void)wi, (void)wo;
  // return Color(0.0f);
  // END TASK
}

float PhongBrdf::diffuse_probability() const {
  const float d = diffuse.x + diffuse.y + diffuse.z, s = specular.x + specular.y + specular.z;
  return d + s > 0.0f ? d / (d + s) : 1.0f;
}

std::optional<BsdfSample> PhongBrdf::sample(Vec3 wo, Vec2 u, float u_lobe) const {
  if (wo.z <= 0.0f) return std::nullopt;
  Vec3 wi;
  if (u_lobe < diffuse_probability()) {
    wi = sample_cosine_hemisphere(u);
  } else {
    const float cos_alpha = std::pow(u.x, 1.0f / (exponent + 1.0f));
    const float sin_alpha = std::sqrt(std::max(0.0f, 1.0f - cos_alpha * cos_alpha));
    const float phi = 2.0f * kPi * u.y;
    wi = Frame::from_normal(mirror_local(wo))
             .to_world(Vec3(sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), cos_alpha));
  }
  if (wi.z <= 0.0f) return std::nullopt;  // the lobe reaches below the surface: a wasted sample
  const float p = pdf(wo, wi);
  if (!(p > 0.0f)) return std::nullopt;
  return BsdfSample{wi, eval(wo, wi) * wi.z / p, p, false};
}

float PhongBrdf::pdf(Vec3 wo, Vec3 wi) const {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return 0.0f;
  const float p_diffuse = diffuse_probability();
  const float lobe = (exponent + 1.0f) * 0.5f * kInvPi * std::pow(lobe_cosine(wo, wi), exponent);
  return p_diffuse * cosine_hemisphere_pdf(wi) + (1.0f - p_diffuse) * lobe;
}

}  // namespace rt
