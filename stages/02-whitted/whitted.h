// Stage 2: Whitted-style recursive ray tracing (Whitted, "An Improved Illumination Model for Shaded
// Display", CACM 23(6), 1980). Follow the camera ray to the nearest surface, then:
//  - diffuse or glossy: shade locally from the point lights, each behind a shadow ray;
//  - mirror: follow the reflected ray, weighted by the mirror's reflectance;
//  - dielectric: follow both the reflected ray (weight F) and the refracted ray (weight 1 - F),
//    or only the reflected one under total internal reflection;
// and add what the surface emits (front face). Rays that escape see the background.
#pragma once

#include "01-ray-casting/ray_caster.h"
#include "02-whitted/optics.h"
#include "02-whitted/ray_offset.h"
#include "02-whitted/whitted_scene.h"

namespace rt {

struct WhittedOptions {
  // Specular bounces followed before a path is cut off: at depth max_depth a mirror or glass
  // surface returns only its emission (black). 0 = local shading only.
  int max_depth = 5;
  FresnelModel fresnel = FresnelModel::exact;
  OffsetPolicy offset;
  // Adaptive tree-depth control (Hall & Greenberg, "A Testbed for Realistic Image Synthesis",
  // IEEE CG&A 3(8), 1983): a branch whose weight (the product of the reflectances and Fresnel
  // factors along it) falls below this is not followed. Glass splits every ray in two, so without
  // it a ray between glass and mirrors costs 2^max_depth rays; with it, the weights at each depth
  // add up to at most 1, so each depth holds at most 1 / min_weight branches. 0 turns it off.
  float min_weight = 1e-4f;
};

// Task stage2.whitted.direct. Light from the point lights reflected towards `wo` at a diffuse
// surface: for each light above the surface that a shadow ray (spawn_shadow_ray) reaches,
// f_r I cos(theta) / r^2 with stage 1's Blinn-Phong BRDF, using the shading normal.
Color shade_direct(const WhittedScene& scene, const Hit& hit, Vec3 wo, const OffsetPolicy& offset);

// The radiance arriving along `ray`, after `depth` specular bounces so far, on a branch of the
// ray tree with the given `weight`.
// Task stage2.whitted.mirror and task stage2.whitted.dielectric are its two recursive cases.
Color whitted_radiance(const WhittedScene& scene, const Ray& ray, const WhittedOptions& options,
                       int depth = 0, float weight = 1.0f);

// The debug views of stage 1 (normal, depth, albedo) for a stage-2 scene. The normal view shows
// the outward SHADING normal, so interpolated mesh normals can be checked by eye.
Color whitted_debug(const WhittedScene& scene, const Ray& ray, DebugView view);

}  // namespace rt
