// Stage 6: light tracing, the path tracer turned round (Arvo, "Backward Ray Tracing", SIGGRAPH 1986
// course notes; Dutre et al., Advanced Global Illumination, section 5.7). Each sample starts a path
// at a light, carrying flux, and at every vertex asks the camera: is this point in view, and how
// much would the pinhole see of the light it scatters that way? That connection is BDPT's strategy
// t = 1, unweighted; the contribution lands on the pixel the point projects to, wherever the sample
// began. It finds what the camera sees of caustics (light -> glass -> floor -> camera) at once, where
// a path tracer needs luck, and it cannot see a mirror or glass at all: a pinhole ray would have to
// leave the delta lobe in exactly the camera's direction (docs/stage6.md, section 3).
#pragma once

#include "06-light-transport/bdpt.h"

namespace rt {

// Task stage6.lt.sample. One light subpath (start_light_subpath, random_walk in importance mode)
// and every one of its vertices, the light's own included, connected to the camera
// (connect_strategy with t = 1); each contribution appended to `splats`.
template <SamplerType S>
void light_tracing_sample(const LightingScene& scene, const Camera& camera, const WalkSettings& walk, S& sampler,
                          std::vector<PathVertex>& light_path, std::vector<Splat>& splats);

}  // namespace rt
