// Stage 4: Monte Carlo direct lighting. The light reflected at x towards wo that arrives straight
// from the emitters is the reflection equation with L_i = the emitted radiance Le seen along wi:
//     L_r(x, wo) = integral_H f_r(wo, wi) Le(x, wi) cos(theta_i) dwi,
// estimated with one sample per camera sample by F = f_r Le cos(theta_i) / p(wi) (the Monte Carlo
// estimator F_N = 1/N sum f(X_k) / p(X_k), averaged over the pixel's samples). Four choices of p,
// all unbiased, so all converge to the same image; they differ only in variance:
//  - uniform_hemisphere: p = 1 / (2 pi); a direction finds a small light only by luck;
//  - cosine_hemisphere:  p = cos(theta) / pi; cancels the cosine, still blind to the lights;
//  - brdf:               p = the BRDF's own sampling density; follows glossy lobes;
//  - light:              pick an emitter by power, a point on it, and convert the density to solid
//                        angle; one shadow ray checks visibility. Finds small lights every time.
// The first three find emitted light by tracing wi to the surface it hits; the fourth by a shadow
// ray to the chosen point. Point lights are Dirac deltas in the integrand: no direction sampler
// can hit them, so every estimator adds each of them exactly, I cos(theta) / r^2 behind a shadow ray.
// Mirrors and glass (delta lobes) are followed by sampling the lobe, up to max_depth bounces, so a
// light seen in a mirror is seen by every estimator.
#pragma once

#include "02-whitted/ray_offset.h"
#include "04-radiometry/lighting_scene.h"
#include "04-radiometry/shading_point.h"
#include "common/frame.h"
#include "common/random.h"

namespace rt {

enum class DirectEstimator { uniform_hemisphere, cosine_hemisphere, brdf, light };

struct DirectOptions {
  DirectEstimator estimator = DirectEstimator::light;
  int max_depth = 5;  // delta (mirror, glass) bounces followed
  OffsetPolicy offset;
};

// Task stage4.direct.point_lights. Sum over the point lights of f_r I cos(theta_i) / r^2 for each
// light a shadow ray (spawn_shadow_ray) reaches.
Color direct_from_point_lights(const LightingScene& scene, const ShadingPoint& at, const OffsetPolicy& offset);

// Task stage4.direct.hemisphere. One direction from the uniform or the cosine-weighted hemisphere
// (per `cosine`): f_r Le cos(theta_i) / p(wi), Le from the emitter the spawned ray hits first.
Color direct_by_hemisphere(const LightingScene& scene, const ShadingPoint& at, bool cosine, Sampler& rng,
                           const OffsetPolicy& offset);

// Task stage4.direct.brdf_sampling. One direction from the BRDF's sample(): weight * Le.
Color direct_by_brdf_sampling(const LightingScene& scene, const ShadingPoint& at, Sampler& rng, const OffsetPolicy& offset);

// One light sample: its estimate, the direction it took and the density it was drawn with (stage 5
// weighs it against the BRDF's density by multiple importance sampling).
struct DirectLightSample {
  Color value{0.0f};  // f_r Le cos(theta_i) / (P p), or 0 (back face, occluded, below the surface)
  Vec3 wi{0.0f};      // local frame
  float pdf = 0.0f;   // P p, per unit solid angle
};

// Task stage4.direct.light_sampling. One emitter chosen by power (probability P) with `u_choice`,
// one point on it (solid-angle density p) with `u`, a shadow ray: f_r Le cos(theta_i) / (P p). The
// environment, when it is the one chosen, gives a direction instead of a point, and its shadow ray
// has no end: the light arrives only if the ray escapes.
// The estimate is a plain function of the numbers (a test can pick them); the overload below draws
// them from a sampler of any type, so the path tracer's stays a concrete type in its own loop (no
// call through the Sampler interface per number; docs/stage5.md, the speed ladder).
DirectLightSample sample_direct_light(const LightingScene& scene, const ShadingPoint& at, float u_choice, Vec2 u,
                                      const OffsetPolicy& offset);
// The same with its numbers drawn from `sampler` (any sampler type, or the Sampler interface): the
// choice first, then the point. With a single emitter there is nothing to choose, and no number is
// drawn for it: each costs a few hashes (docs/stage5.md, the speed ladder, step 15).
template <SamplerType S>
DirectLightSample sample_direct_light(const LightingScene& scene, const ShadingPoint& at, S& sampler,
                                      const OffsetPolicy& offset) {
  const float u_choice = scene.emitter_distribution().size() > 1 ? sampler.uniform() : 0.5f;
  return sample_direct_light(scene, at, u_choice, sampler.uniform2(), offset);
}
inline Color direct_by_light_sampling(const LightingScene& scene, const ShadingPoint& at, Sampler& rng,
                                      const OffsetPolicy& offset) {
  return sample_direct_light(scene, at, rng, offset).value;
}

// The radiance arriving along a camera ray: what the first surface emits plus, for a non-delta
// surface, its direct lighting (point lights, and one sample of the area emitters by the chosen
// estimator); a delta surface passes on what its sampled lobe sees.
Color direct_radiance(const LightingScene& scene, const Ray& ray, const DirectOptions& options, Sampler& rng, int depth = 0);

}  // namespace rt
