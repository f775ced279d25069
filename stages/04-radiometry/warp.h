// Stage 4: sample warps. Each turns uniform numbers u in [0, 1)^2 into a point or direction with a
// known density, and sits next to that density: a sample function and its pdf always come as a
// pair, so an estimator f(X) / p(X) can never pair a sampler with the wrong density.
//
// Directions are in the local shading frame (common/frame.h): the normal is +z, theta is measured
// from it, and densities are per unit SOLID ANGLE (sr^-1). Points on a disk or triangle have
// densities per unit AREA. Every warp here is tested by a chi-square goodness-of-fit test against
// its pdf (tests/stage4/warp_test.cpp).
#pragma once

#include "01-ray-casting/disk_sampling.h"
#include "common/math.h"

namespace rt {

// ---- Hemisphere and sphere ------------------------------------------------------------------

// The unit vector at polar angle theta (given by its cosine) and azimuth phi about +z.
Vec3 from_cos_theta_phi(float cos_theta, float phi);

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


// The unit disk's uniform sample (Shirley and Chiu's concentric map), its pdf and its inverse are
// stage 1's, where the thin lens first needs them: 01-ray-casting/disk_sampling.h.

// Task stage4.warp.triangle. Barycentrics (b0, b1, b2) of a point uniform over a triangle:
// b0 = 1 - sqrt(u0), b1 = u1 sqrt(u0) (Turk, "Generating Random Points in Triangles", Graphics Gems,
// 1990; the square root undoes the triangle's width growing linearly). The density is 1 / area.
Vec3 sample_uniform_triangle(Vec2 u);

// ---- Inverses -------------------------------------------------------------------------------
// Each returns the u that the warp of the same name maps to its argument (pbrt-v4 keeps such an
// inverse beside every warp): what a stratified or low-discrepancy sampler needs to place a given
// point or direction, and what the tests use to check that a warp is one to one. Arguments are
// points or directions the warp can produce (on the disk, above the surface, inside the cone).
Vec2 invert_uniform_hemisphere(Vec3 w);
Vec2 invert_uniform_sphere(Vec3 w);
Vec2 invert_cosine_hemisphere(Vec3 w);
Vec2 invert_uniform_cone(Vec3 w, float cos_theta_max);
// From barycentrics: u0 = (1 - b0)^2, u1 = b1 / (1 - b0).
Vec2 invert_uniform_triangle(Vec3 b);

}  // namespace rt
