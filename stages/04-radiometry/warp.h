// Stage 4: sample warps. Each turns uniform numbers u in [0, 1)^2 into a point or direction with a
// known density, and sits next to that density: a sample function and its pdf always come as a
// pair, so an estimator f(X) / p(X) can never pair a sampler with the wrong density.
//
// Directions are in the local shading frame (common/frame.h): the normal is +z, theta is measured
// from it, and densities are per unit SOLID ANGLE (sr^-1). Points on a disk or triangle have
// densities per unit AREA. Every warp here is tested by a chi-square goodness-of-fit test against
// its pdf (tests/stage4/warp_test.cpp).
#pragma once

#include "common/math.h"

namespace rt {

// ---- Hemisphere and sphere ------------------------------------------------------------------

// Uniform over the upper hemisphere: z = u0, phi = 2 pi u1 (dw = dz dphi, so a uniform z is a
// uniform solid angle: Archimedes' hat-box theorem). pdf = 1 / (2 pi).
Vec3 sample_uniform_hemisphere(Vec2 u);
inline float uniform_hemisphere_pdf(Vec3 w) { return w.z >= 0.0f ? 0.5f * kInvPi : 0.0f; }

// Uniform over the whole sphere: z = 1 - 2 u0. pdf = 1 / (4 pi).
Vec3 sample_uniform_sphere(Vec2 u);
inline float uniform_sphere_pdf() { return 0.25f * kInvPi; }

// Task stage4.warp.cosine_hemisphere. Cosine-weighted hemisphere, pdf = cos(theta) / pi, by
// Malley's method: a uniform point on the unit disk (sample_uniform_disk) lifted straight up to the
// hemisphere, z = sqrt(1 - x^2 - y^2) (PBR 4th ed. section A.5.3).
Vec3 sample_cosine_hemisphere(Vec2 u);
inline float cosine_hemisphere_pdf(Vec3 w) { return w.z > 0.0f ? w.z * kInvPi : 0.0f; }

// Task stage4.warp.cone. Uniform over the cone of directions within theta_max of +z:
// cos(theta) = 1 - u0 (1 - cos_theta_max), phi = 2 pi u1. pdf = 1 / (2 pi (1 - cos_theta_max)), the
// inverse of the cone's solid angle. Used to sample a sphere light by the cone it subtends.
Vec3 sample_uniform_cone(Vec2 u, float cos_theta_max);
inline float uniform_cone_pdf(float cos_theta_max) { return 1.0f / (2.0f * kPi * (1.0f - cos_theta_max)); }

// ---- Disk and triangle (area densities) -------------------------------------------------------

// Task stage4.warp.concentric_disk. Uniform over the unit disk by Shirley and Chiu's concentric
// map ("A Low Distortion Map Between Disk and Square", JGT 2(3), 1997): the square's concentric
// squares go to the disk's concentric circles, so strata stay compact. pdf = 1 / pi per unit area.
Vec2 sample_uniform_disk(Vec2 u);
inline float uniform_disk_pdf(Vec2 p) { return p.x * p.x + p.y * p.y <= 1.0f ? kInvPi : 0.0f; }

// Task stage4.warp.triangle. Barycentrics (b0, b1, b2) of a point uniform over a triangle:
// b0 = 1 - sqrt(u0), b1 = u1 sqrt(u0) (Turk, "Generating Random Points in Triangles", Graphics Gems,
// 1990; the square root undoes the triangle's width growing linearly). The density is 1 / area.
Vec3 sample_uniform_triangle(Vec2 u);

// ---- The GGX microfacet distribution ----------------------------------------------------------
// Trowbridge & Reitz (1975), named GGX by Walter, Marschner, Li & Torrance ("Microfacet Models for
// Refraction through Rough Surfaces", EGSR 2007). alpha is the roughness (the slope spread);
// m is a microfacet normal in the local frame.

// D(m) = alpha^2 / (pi ((alpha^2 - 1) cos^2 theta_m + 1)^2), Walter et al. eq. 33; it is normalized
// so that the projected microfacet area is the macro-surface's: integral D(m) cos theta_m dm = 1.
float ggx_ndf(Vec3 m, float alpha);
// Smith's Lambda for GGX, (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2 (Heitz, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), 2014, eq. 72).
float ggx_lambda(Vec3 w, float alpha);
// Smith masking of one direction, G1 = 1 / (1 + Lambda(w)).
inline float ggx_smith_g1(Vec3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }

// Microfacet normals distributed as D(m) cos(theta_m) (Walter et al. eq. 35-36):
// tan^2 theta = alpha^2 u0 / (1 - u0), phi = 2 pi u1. pdf = D(m) cos(theta_m).
Vec3 sample_ggx_normal(Vec2 u, float alpha);
inline float ggx_normal_pdf(Vec3 m, float alpha) { return m.z > 0.0f ? ggx_ndf(m, alpha) * m.z : 0.0f; }

// Task stage4.warp.ggx_visible. Only the normals visible from wo, distributed as
// D_wo(m) = G1(wo) max(0, wo . m) D(m) / cos(theta_o) (Heitz, "Sampling the GGX Distribution of
// Visible Normals", JCGT 7(4), 2018): stretch wo to the alpha = 1 configuration, sample the
// projected hemisphere there, unstretch. Samples never face away from wo, so none is wasted.
Vec3 sample_ggx_visible_normal(Vec3 wo, Vec2 u, float alpha);
float ggx_visible_normal_pdf(Vec3 wo, Vec3 m, float alpha);

}  // namespace rt
