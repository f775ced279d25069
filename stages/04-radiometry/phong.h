// Stage 4: the modified, normalized Phong BRDF (Lafortune & Willems, "Using the Modified Phong
// Reflectance Model for Physically Based Rendering", KU Leuven CW 197, 1994):
//     f_r = rho_d / pi + rho_s (n + 2) / (2 pi) cos^n(alpha),
// alpha the angle between wi and the mirror direction of wo. Unlike stage 1's empirical highlight,
// it is reciprocal (cos alpha is symmetric in wi and wo) and, with rho_d + rho_s <= 1, reflects
// no more than it receives: (n + 2) / (2 pi) makes the lobe's albedo exactly rho_s at normal
// incidence, its largest value.
#pragma once

#include "04-radiometry/bsdf_sample.h"

#include <optional>

namespace rt {

struct PhongBrdf {
  Color diffuse;   // rho_d
  Color specular;  // rho_s, with rho_d + rho_s <= 1 per channel
  float exponent;  // n >= 0: larger is glossier

  // Task stage4.brdf.phong: f_r as above, when wi and wo are both above the surface.
  Color eval(Vec3 wo, Vec3 wi) const;
  // A mixture: with probability diffuse_probability() a cosine-weighted direction, otherwise one
  // from the lobe, cos(alpha) = u0^(1 / (n + 1)) about the mirror direction, whose density is
  // (n + 1) / (2 pi) cos^n(alpha). The pdf is the mixture's, so either choice gives the same
  // weight for the same wi (one-sample MIS with the balance heuristic).
  std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe) const;
  float pdf(Vec3 wo, Vec3 wi) const;
  // The probability of sampling the diffuse part: its share of the total reflectance.
  float diffuse_probability() const;
};

}  // namespace rt
