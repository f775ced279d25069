// Stage 4: radiometry in code. The quantities, with units (per RGB channel):
//     flux        Phi  [W]                  power leaving a light or arriving at a surface
//     intensity   I    [W sr^-1]            flux per solid angle from a point: I = dPhi / dw
//     irradiance  E    [W m^-2]             flux arriving per unit area: E = dPhi / dA
//     radiance    L    [W m^-2 sr^-1]       flux per unit projected area per solid angle:
//                                           L = d^2 Phi / (dA cos(theta) dw)
// Solid angle: the area a set of directions covers on the unit sphere, in steradians; in
// spherical coordinates dw = sin(theta) dtheta dphi, so the hemisphere has 2 pi sr.
// A patch dA at distance r, tilted by theta' from the direction back to the viewer, covers
//     dw = dA cos(theta') / r^2,
// the change of variables that turns a density over an emitter's area into one over solid angle.
#pragma once

#include "common/math.h"

#include <span>

namespace rt {

// Solid angle of a cone of half-angle theta_max: 2 pi (1 - cos(theta_max)).
inline float cone_solid_angle(float cos_theta_max) { return 2.0f * kPi * (1.0f - cos_theta_max); }

// Task stage4.radiometry.area_to_solid_angle. A density over an emitter's area turned into one
// over the solid angle seen from a point at `distance`, where the emitter's normal makes an angle
// with cosine `cos_light` to the direction back to that point: p_w = p_A r^2 / |cos(theta')|,
// from dw = dA cos(theta') / r^2. Edge-on (cos = 0) the density is infinite.
float area_to_solid_angle_pdf(float pdf_area, float distance, float cos_light);

// Irradiance from a point light of intensity I at distance r, arriving at an angle theta to the
// normal: E = I cos(theta) / r^2 (the inverse-square law and Lambert's cosine law).
inline Color point_light_irradiance(Color intensity, float distance, float cos_theta) {
  return intensity * (std::max(0.0f, cos_theta) / (distance * distance));
}

// Radiance reflected by a Lambertian surface of albedo rho under irradiance E: L = rho E / pi.
inline Color lambertian_radiance(Color albedo, Color irradiance) { return albedo * irradiance * kInvPi; }

// Flux leaving a one-sided Lambertian emitter of radiance L and area A: Phi = pi L A (the cosine
// integrates to pi over the hemisphere). A point light of intensity I sends Phi = 4 pi I.
inline Color lambertian_emitter_flux(Color radiance, float area) { return radiance * (kPi * area); }
inline Color point_light_flux(Color intensity) { return intensity * (4.0f * kPi); }

// Task stage4.radiometry.polygon_irradiance. Irradiance at point p with unit normal n from a
// planar polygon of uniform radiance L lying wholly above p's tangent plane, by Lambert's formula
// (Lambert, Photometria, 1760; in vector form Arvo, "Applications of Irradiance Tensors to the
// Simulation of Non-Lambertian Phenomena", SIGGRAPH 1995, eq. 9):
//     E = L/2 |sum_i Theta_i (Gamma_i . n)|,
// with u_i the unit vector from p to vertex i, Theta_i = angle between u_i and u_{i+1}, and
// Gamma_i = (u_i x u_{i+1}) / |u_i x u_{i+1}|. It is exact, which makes it the oracle for area
// light sampling (a quad light sampled as two triangles must reproduce it).
float polygon_irradiance(Vec3 p, Vec3 n, std::span<const Vec3> vertices, float radiance);

}  // namespace rt
