// Stage 2: geometric optics at a smooth surface: the law of reflection, Snell's law, and how much
// light each takes (Fresnel: exact, and Schlick's curve, which stage 4's metals use too).
//
// Conventions: `d` is the direction the ray travels (towards the surface), `n` the unit normal on
// the side the ray comes from (Hit::normal, so d.n < 0), and cos_i = -d.n > 0. eta_i and eta_t are
// the indices of refraction on the incident and transmitted sides.
#pragma once

#include "common/math.h"

#include <algorithm>

#include <optional>

namespace rt {

// Task stage2.optics.reflect. Mirror reflection: the angle of incidence equals the angle of
// reflection, r = d - 2 (d.n) n.
Vec3 reflect(Vec3 d, Vec3 n);

// Task stage2.optics.refract. Snell's law, eta_i sin(theta_i) = eta_t sin(theta_t). With
// eta = eta_i / eta_t:
//     sin^2(theta_t) = eta^2 (1 - cos^2(theta_i));     t = eta d + (eta cos_i - cos_t) n,
// with cos_t = sqrt(1 - sin^2(theta_t)). Returns nothing beyond the critical angle,
// sin^2(theta_t) > 1: total internal reflection.
std::optional<Vec3> refract(Vec3 d, Vec3 n, float eta_i, float eta_t);

// Task stage2.optics.fresnel. The exact Fresnel reflectance of a dielectric interface for
// unpolarized light: the mean of the s and p power reflectances,
//     r_s = (eta_i cos_i - eta_t cos_t) / (eta_i cos_i + eta_t cos_t),
//     r_p = (eta_t cos_i - eta_i cos_t) / (eta_t cos_i + eta_i cos_t),   F = (r_s^2 + r_p^2) / 2,
// and F = 1 under total internal reflection. The transmitted fraction is 1 - F (no absorption).
// At normal incidence F = ((eta_t - eta_i) / (eta_t + eta_i))^2, 0.04 for glass (1.5) in air.
float fresnel_dielectric(float cos_i, float eta_i, float eta_t);

// Schlick's approximation (Schlick, "An Inexpensive BRDF Model for Physically-based Rendering",
// CGF 13(3), 1994): F = F0 + (1 - F0)(1 - cos)^5, F0 the reflectance at normal incidence, for one
// value or per channel (a metal's coloured F0, stage 4). The one place the curve is written.
template <class Value>
Value schlick(Value f0, float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (Value(1.0f) - f0) * (m2 * m2 * m);
}

// Task stage2.optics.schlick. Schlick's approximation for a dielectric interface: the curve above
// with F0 = ((eta_t - eta_i) / (eta_t + eta_i))^2, where cos is taken on the optically THINNER side
// (cos_t when leaving glass), and F = 1 under total internal reflection.
float fresnel_schlick(float cos_i, float eta_i, float eta_t);

enum class FresnelModel { exact, schlick };

inline float fresnel(FresnelModel model, float cos_i, float eta_i, float eta_t) {
  return model == FresnelModel::schlick ? fresnel_schlick(cos_i, eta_i, eta_t)
                                        : fresnel_dielectric(cos_i, eta_i, eta_t);
}

}  // namespace rt
