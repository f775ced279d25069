// Stage 6: stochastic progressive photon mapping (Hachisuka & Jensen, "Stochastic Progressive
// Photon Mapping", SIGGRAPH Asia 2009; built on Hachisuka, Ogaki & Jensen, "Progressive Photon
// Mapping", SIGGRAPH Asia 2008). Photon mapping (Jensen 1996) estimates the light reflected at x
// from the photons that landed within r of it, a density estimate:
//     L(x, wo) ~ 1 / (N pi r^2) sum_p f(wo, wi_p) Phi_p,
// N photons emitted, Phi_p each one's flux times N. It is biased (the light is blurred over the
// disk of radius r) and its noise falls as r grows: one r cannot make both vanish. The progressive
// form runs passes, and at each pixel's visible point shrinks r as photons arrive, keeping a share
// alpha of the new ones (alpha = 2/3 by default):
//     N_i+1 = N_i + alpha M_i,   r_i+1 = r_i sqrt(N_i+1 / (N_i + M_i)),
//     tau_i+1 = (tau_i + Phi_i) r_i+1^2 / r_i^2,
// so both the bias and the variance go to 0: the estimate is consistent (Knaus & Zwicker,
// "Progressive Photon Mapping: A Probabilistic Approach", 2011, give the rates). Each pass
// traces, per pixel, a camera path through mirrors and glass to its first other surface (the
// visible point, where direct light is sampled as in stage 4), then a batch of photons from the
// lights, which are gathered at the visible points. Paths light -> glass -> floor -> glass -> eye
// (a caustic seen through glass), which no path or light tracer can sample, are found here.
#pragma once

#include "05-path-tracing/path_tracer.h"
#include "06-light-transport/path_vertex.h"
#include "common/progress.h"
#include "common/sample_sums.h"

namespace rt {

struct SppmOptions {
  int photons_per_pass = 100000;
  // r_0 in scene units; 0: kFootprintRadii pixel footprints at each pixel's first visible point.
  float initial_radius = 0.0f;
  float alpha = 2.0f / 3.0f;
  int max_depth = 10;  // mirror and glass bounces a camera path follows to its visible point
  WalkSettings walk;   // the photons' walk (Russian roulette as stage 5's)
};

// r_0 when none is given, in pixel footprints (a pixel's angular width times the distance to the
// visible point), so that the blur starts at the scale the image resolves, whatever the scene's
// units and the resolution. Measured in docs/stage6.md, section 5.
inline constexpr float kFootprintRadii = 1.0f;

// One pixel's progressive statistics.
struct PhotonStatistics {
  double photons = 0.0;  // N: the photons it has kept
  float radius = 0.0f;   // r
  Color tau{0.0f};       // the flux gathered within r, rescaled to the current r
};

// Task stage6.sppm.update. One pass's photons at a pixel: M found within r, Phi their flux
// (sum of beta f Phi_p): the reduction above. With M = 0 nothing changes.
void progressive_update(PhotonStatistics& stats, int found, Color flux, float alpha);

// The pixel's reflected radiance from the photons so far, tau / (pi r^2 N_emitted).
Color photon_radiance(const PhotonStatistics& stats, double photons_emitted);

// Task stage6.sppm.gather. The photons within `radius` of the visible point `at`, and the flux
// they bring towards at.wo: sum over them of f(wo, wi_p) Phi_p (no cosine: a photon's flux already
// counts the area it lands on).
class PhotonGrid;
struct Gathered {
  int found = 0;
  Color flux{0.0f};
};
Gathered gather_photons(const PhotonGrid& grid, const ShadingPoint& at, float radius);

// The whole render: settings.spp passes, photons_per_pass photons each. Per pixel of the window, the
// estimate after the passes it finished (the mean of its direct light over the passes plus the
// photons' radiance) times that number, with the number as the count, so that SampleSums::mean is
// the image. The same bit for bit for any thread count: photons are traced in fixed chunks and
// gathered in the grid's fixed order. A stop request ends it between two passes. Camera rays are
// uniform over each pixel (the box filter, whatever settings.filter says; the program refuses others).
SampleSums render_sppm(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                       const SppmOptions& options, int threads, SampleGuard& guard, ProgressBar* progress = nullptr);

}  // namespace rt
