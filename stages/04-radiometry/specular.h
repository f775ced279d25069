// Stage 4: stage 2's perfect mirror and glass as delta lobes behind the BRDF contract
// (04-radiometry/brdf.h). Each reflects (or transmits) into one direction only, so eval() and pdf()
// are 0 and only sample() can find that direction.
#pragma once

#include "04-radiometry/bsdf_sample.h"

#include <optional>

namespace rt {

struct MirrorBrdf {
  Color reflectance;

  Color eval(Vec3, Vec3) const { return Color(0.0f); }
  // wi = mirror_local(wo) = (-wo.x, -wo.y, wo.z), weight = reflectance, probability 1.
  std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe) const;
  float pdf(Vec3, Vec3) const { return 0.0f; }
};

// Glass: reflect with probability F (exact Fresnel, stage 2's optics), otherwise refract, so that
// the weight is 1 for reflection and, for radiance, (eta_o / eta_i)^2 for refraction. Radiance,
// unlike flux, is not conserved across an interface: it is squeezed into a narrower cone on the
// denser side, L_t = (1 - F) (eta_t / eta_i)^2 L_i (PBR 4th ed. section 9.5.2). Importance is
// carried as flux is, and its refraction weighs 1 (bsdf.h, TransportMode).
struct DielectricBsdf {
  float eta_outside;  // index on the side wo is on (the +z side)
  float eta_inside;   // index on the other side

  Color eval(Vec3, Vec3) const { return Color(0.0f); }
  std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe, TransportMode mode) const;
  float pdf(Vec3, Vec3) const { return 0.0f; }
};

}  // namespace rt
