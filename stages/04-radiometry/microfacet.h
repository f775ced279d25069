// Stage 4: a rough metal as a GGX microfacet BRDF (Cook & Torrance 1982; Walter et al., EGSR 2007,
// eq. 20, with Smith's height-correlated masking-shadowing, Heitz JCGT 2014 eq. 99):
//     f_r = F(wi . h) D(h) G2(wi, wo) / (4 cos(theta_i) cos(theta_o)),   h = (wi + wo) / |wi + wo|.
// F is Schlick's approximation F0 + (1 - F0)(1 - wi . h)^5 with a coloured F0. Each microfacet is a
// perfect mirror; the model reflects once, so energy that would take several bounces among the
// microfacets is lost and the albedo falls below 1 as the roughness grows (never above).
#pragma once

#include "04-radiometry/brdf_sample.h"

#include <optional>

namespace rt {

struct MicrofacetBrdf {
  Color f0;     // reflectance at normal incidence, per channel
  float alpha;  // GGX roughness, > 0

  // Task stage4.brdf.microfacet: f_r as above, when wi and wo are both above the surface.
  Color eval(Vec3 wi, Vec3 wo) const;
  // Samples a visible normal m (stage4.warp.ggx_visible) and reflects wo about it. The density of
  // wi is that of m times the Jacobian of the reflection, dm / dwi = 1 / (4 |wo . m|) (Walter et al.
  // eq. 14), which leaves pdf = G1(wo) D(m) / (4 cos(theta_o)) and weight = F G2 / G1(wo) <= 1.
  std::optional<BrdfSample> sample(Vec3 wo, Vec2 u, float u_lobe) const;
  float pdf(Vec3 wi, Vec3 wo) const;
};

// Schlick's Fresnel approximation with a coloured F0 (Schlick, "An Inexpensive BRDF Model for
// Physically-based Rendering", CGF 13(3), 1994).
Color fresnel_schlick_f0(Color f0, float cos_theta);

}  // namespace rt
