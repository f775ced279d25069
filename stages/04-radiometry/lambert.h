// Stage 4: the Lambertian BRDF, f_r = rho / pi: the same radiance towards every direction. Its
// directional albedo is rho for every wo, because the cosine integrates to pi over the hemisphere.
#pragma once

#include "04-radiometry/bsdf_sample.h"

#include <optional>

namespace rt {

struct LambertBrdf {
  Color albedo;  // rho, in [0, 1] per channel

  // Task stage4.brdf.lambert: f_r = rho / pi when wi and wo are both above the surface.
  Color eval(Vec3 wo, Vec3 wi) const;
  // Cosine-weighted sampling (stage4.warp.cosine_hemisphere): pdf = cos(theta_i) / pi, so the
  // weight f cos / pdf is exactly rho.
  std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe) const;
  float pdf(Vec3 wo, Vec3 wi) const;
};

}  // namespace rt
