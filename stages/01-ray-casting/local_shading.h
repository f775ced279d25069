// Stage 1: local shading. Light arrives only straight from point lights, blocked or not by a hard
// shadow ray; there is no reflected light between surfaces yet (that is stage 2 and beyond).
//
// A point light of intensity I (W/sr) at distance r, seen at angle theta from the normal, gives
// irradiance E = I cos(theta) / r^2 (inverse-square and Lambert's cosine law), and the surface
// sends L = f_r E towards the viewer.
#pragma once

#include "01-ray-casting/ray_casting_scene.h"

namespace rt {

// Task stage1.shading.brdf. The BRDF of the diffuse material: Lambert plus a normalized
// Blinn-Phong lobe,
//   f_r = albedo / pi + specular * (s + 8) / (8 pi) * max(0, n.h)^s,   h = normalize(wi + wo),
// with `albedo` the diffuse reflectance at the shaded point (material.albedo_at(point), which
// differs from material.albedo on a checkered surface).
// The 1/pi makes a white Lambertian surface reflect exactly what it receives; (s + 8) / (8 pi) is
// the usual approximate normalization of the Blinn-Phong lobe (Akenine-Moeller et al.,
// Real-Time Rendering, 4th ed., section 9.8), which keeps its highlight's energy roughly
// constant as the exponent s changes. All directions are unit vectors pointing AWAY from the
// surface, wo (towards the viewer) first, as in every BRDF of the framework; n is on the viewer's
// side.
Color blinn_phong_brdf(const Material& material, Color albedo, Vec3 n, Vec3 wo, Vec3 wi);

// Task stage1.shading.local. Radiance leaving hit.point towards `to_viewer`: the material's
// emission (front face only) plus, for every point light above the surface (n.wi > 0) that a
// shadow ray reaches, f_r * I * cos(theta) / r^2.
// The shadow ray starts kShadowRayOffset along the normal, the fixed-epsilon cure for shadow acne
// that stage 2 replaces with an offset scaled to the hit point's rounding error.
Color shade_local(const RayCastingScene& scene, const Hit& hit, Vec3 to_viewer);

inline constexpr float kShadowRayOffset = 1e-4f;

}  // namespace rt
