// Stage 6: light leaving the emitters. Stage 4 samples a light towards a point it is lighting (a
// direction from x); light tracing, BDPT and photon mapping start paths AT the light instead, so
// they sample where light leaves and in which direction: an emitter by power (stage 4's
// distribution), a point uniform over its area, and, since every emitter here is Lambertian (the
// same Le in every direction of its front hemisphere), a cosine-weighted direction about its normal,
// which makes the flux each sample carries the same everywhere:
//     beta = Le cos(theta) / (P_choice p_A p_w) = Le cos(theta) / (P_choice (1/A) (cos(theta) / pi))
//          = pi A Le / P_choice,
// the emitter's flux over the probability of choosing it (PBR 4th ed. section 12.2).
#pragma once

#include "02-whitted/ray_offset.h"
#include "04-radiometry/lighting_scene.h"
#include "06-light-transport/path_vertex.h"

#include <optional>

namespace rt {

// A point on an emitter: a Hit (point, the front normal, a bound on the point's rounding error, so
// stage 2's offsets apply to rays leaving it) and the emitter's index.
struct EmitterPoint {
  Hit hit;
  int emitter = -1;
};

// A uniform point on the emitter's surface (density 1 / area), with its front normal.
EmitterPoint sample_emitter_point(const AreaEmitter& emitter, int index, Vec2 u);

struct EmissionSample {
  EmitterPoint origin;
  Vec3 direction;        // unit, world, into the front hemisphere
  Color radiance;        // Le along it
  float pdf_position;    // P_choice / area: per unit area, the choice included
  float pdf_direction;   // cos(theta) / pi, per unit solid angle
};

// Task stage6.light.emission. An emitter chosen by power with u_choice (stage 4's
// emitter_distribution), a uniform point on it with u_position, a cosine-weighted direction about
// its front normal with u_direction. Nothing when the scene has no area emitter.
std::optional<EmissionSample> sample_emission(const LightingScene& scene, float u_choice, Vec2 u_position,
                                              Vec2 u_direction);

// The density of choosing emitter `index` and then a point on it, per unit area: P_choice / area.
float emission_position_pdf(const LightingScene& scene, int index);
// The density of the emitted direction w at a point whose front normal is n: cos(theta) / pi in
// front, 0 behind.
float emission_direction_pdf(Vec3 front_normal, Vec3 w);

// The light vertex y_0 at a point on an emitter sampled with area density pdf_position (the choice
// included): beta = Le / pdf_position, what every strategy multiplies by the light's side.
PathVertex light_vertex(const EmitterPoint& point, Color radiance, float pdf_position);

// The light vertex y_0 of an emission sample, and the start of its subpath: where light tracing,
// BDPT and photon mapping all begin a light subpath.
struct LightSubpathStart {
  PathVertex origin;
  Ray ray;
  Color beta;   // after the emission: Le cos / (P_choice p_A p_w)
  float pdf_w;  // of the emitted direction
};
template <SamplerType S>
std::optional<LightSubpathStart> start_light_subpath(const LightingScene& scene, S& sampler,
                                                     const OffsetPolicy& offset);

}  // namespace rt
