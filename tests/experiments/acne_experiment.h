// Stage 2: the scale experiment behind docs/charts/stage2-offset-vs-scale.png and the test
// ShadowAcne.*: a plane, a sphere above it and a point light, the whole scene scaled by s (and
// rotated and moved by 0.3 s so that no coordinate is round). For each pixel the renderer's shadow
// decision (float, with an offset policy) is compared with the exact one (double, from the same
// float camera ray).
#pragma once

#include "02-whitted/ray_offset.h"
#include "common/scene.h"

namespace rt {

// The scene at scale s: a plane (grey), a unit-radius sphere (times s) resting 0.3 s above it, one
// point light, and a camera that sees the sphere, its shadow and open floor.
SceneDescription make_acne_scene(float scale, int width, int height);

struct ShadowErrors {
  int pixels = 0;  // pixels compared (silhouettes and shadow boundaries excluded)
  int acne = 0;    // lit in truth, shadowed by the renderer (self-intersection)
  int leaks = 0;   // shadowed in truth, lit by the renderer (offset past the occluder)
  int wrong() const { return acne + leaks; }
};

// Counts wrong shadow decisions over one pixel-centre ray per pixel. A pixel is left out where
// the exact answer is within 1e-3 (in units of the sphere's radius) of changing: at the sphere's
// silhouette, at its terminator, and at the edge of its shadow.
ShadowErrors count_shadow_errors(float scale, const OffsetPolicy& policy, int width, int height);

}  // namespace rt
