#include "04-radiometry/specular.h"

#include "02-whitted/optics.h"
#include "common/frame.h"

namespace rt {

std::optional<BsdfSample> MirrorBrdf::sample(Vec3 wo, Vec2, float) const {
  if (wo.z <= 0.0f) return std::nullopt;
  return BsdfSample{mirror_local(wo), reflectance, 1.0f, true};
}

std::optional<BsdfSample> DielectricBsdf::sample(Vec3 wo, Vec2, float u_lobe, TransportMode mode) const {
  if (wo.z <= 0.0f) return std::nullopt;
  const Vec3 normal(0.0f, 0.0f, 1.0f);
  const float f = fresnel_dielectric(wo.z, eta_outside, eta_inside);
  if (u_lobe < f) return BsdfSample{mirror_local(wo), Color(1.0f), f, true};
  const std::optional<Vec3> wt = refract(-wo, normal, eta_outside, eta_inside);
  if (!wt) return BsdfSample{mirror_local(wo), Color(1.0f), 1.0f, true};  // total internal reflection
  const float scale = mode == TransportMode::radiance ? eta_outside / eta_inside : 1.0f;
  return BsdfSample{*wt, Color(scale * scale), 1.0f - f, true};
}

}  // namespace rt
