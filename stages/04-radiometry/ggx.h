// Stage 4: the GGX microfacet distribution (Trowbridge & Reitz 1975, named GGX by Walter,
// Marschner, Li & Torrance, "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007),
// as one object that owns everything a microfacet BSDF asks of it: the distribution of normals D,
// Smith's masking Lambda, G1 and the height-correlated G2, and the sampling of normals (all of
// them, or only those wo sees) with their densities. alpha is the roughness (the slope spread); m
// is a microfacet normal and w a direction, both in the local frame (normal +z).
#pragma once

#include "common/math.h"

namespace rt {

struct GgxDistribution {
  float alpha;  // > 0

  // D(m) = alpha^2 / (pi ((alpha^2 - 1) cos^2 theta_m + 1)^2), Walter et al. eq. 33; normalized
  // so that the projected microfacet area is the macro-surface's: integral D(m) cos theta_m dm = 1.
  float d(Vec3 m) const;
  // Smith's Lambda for GGX, (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2 (Heitz, "Understanding the
  // Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), 2014, eq. 72).
  float lambda(Vec3 w) const;
  // Masking of one direction, G1 = 1 / (1 + Lambda(w)).
  float g1(Vec3 w) const { return 1.0f / (1.0f + lambda(w)); }
  // Height-correlated masking-shadowing, G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz eq. 99).
  float g2(Vec3 wo, Vec3 wi) const { return 1.0f / (1.0f + lambda(wi) + lambda(wo)); }

  // Normals distributed as D(m) cos(theta_m) (Walter et al. eq. 35-36):
  // tan^2 theta = alpha^2 u0 / (1 - u0), phi = 2 pi u1. pdf = D(m) cos(theta_m).
  Vec3 sample_normal(Vec2 u) const;
  float normal_pdf(Vec3 m) const { return m.z > 0.0f ? d(m) * m.z : 0.0f; }

  // Task stage4.warp.ggx_visible. Only the normals visible from wo, distributed as
  // D_wo(m) = G1(wo) max(0, wo . m) D(m) / cos(theta_o) (Heitz, "Sampling the GGX Distribution of
  // Visible Normals", JCGT 7(4), 2018): stretch wo to the alpha = 1 configuration, sample the
  // projected hemisphere there, unstretch. Samples never face away from wo, so none is wasted.
  Vec3 sample_visible_normal(Vec3 wo, Vec2 u) const;
  float visible_normal_pdf(Vec3 wo, Vec3 m) const;
};

}  // namespace rt
