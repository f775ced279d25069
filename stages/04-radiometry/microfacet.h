// Stage 4: a rough metal as a GGX microfacet BRDF (Cook & Torrance 1982; Walter et al., EGSR 2007,
// eq. 20, with Smith's height-correlated masking-shadowing, Heitz JCGT 2014 eq. 99):
//     f_r = F(wi . h) D(h) G2(wo, wi) / (4 cos(theta_o) cos(theta_i)),   h = (wo + wi) / |wo + wi|.
// D and G2 are the GGX distribution's (04-radiometry/ggx.h); F is Schlick's approximation with a
// coloured F0 (02-whitted/optics.h). Each microfacet is a perfect mirror; the model reflects once,
// so energy that would take several bounces among the microfacets is lost and the albedo falls
// below 1 as the roughness grows (never above).
#pragma once

#include "04-radiometry/bsdf_sample.h"
#include "04-radiometry/ggx.h"

#include <optional>

namespace rt {

struct MicrofacetBrdf {
  Color f0;  // reflectance at normal incidence, per channel
  GgxDistribution ggx;

  // Task stage4.brdf.microfacet: f_r as above, when wi and wo are both above the surface.
  Color eval(Vec3 wo, Vec3 wi) const;
  // Samples a normal m visible from wo (stage4.warp.ggx_visible) and reflects wo about it. The density of
  // wi is that of m times the Jacobian of the reflection, dm / dwi = 1 / (4 |wo . m|) (Walter et al.
  // eq. 14), which leaves pdf = G1(wo) D(m) / (4 cos(theta_o)) and weight = F G2 / G1(wo) <= 1.
  std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe) const;
  float pdf(Vec3 wo, Vec3 wi) const;
};

}  // namespace rt
