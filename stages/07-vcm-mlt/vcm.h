// Stage 7: vertex connection and merging (vcm_weight.h has the estimator's weights). An iteration
// traces N light subpaths (one per pixel, or as many as its budget asks: vcm_budget.h), connects
// each light vertex to the camera (light tracing, splatted), and stores the vertices in stage 6's
// photon grid; then one camera subpath per pixel (or as many as the budget's plan gives the pixel),
// and at each of its vertices z:
//   - the light it hits (s = 0), a fresh light point (s = 1, next-event estimation), and the
//     connections to every vertex of its own pixel's light subpath (stage 6's BDPT strategies);
//   - a merge with every light vertex y within r of z: z's throughput, f at z, y's throughput,
//     divided by eta = N pi r^2, photon mapping's density estimate (stage 6's sppm.h) for one path.
// The radius shrinks from one iteration to the next, r_i = r_1 i^((alpha - 1) / 2) (Knaus &
// Zwicker, "Progressive Photon Mapping: A Probabilistic Approach", 2011), so the merges' bias
// vanishes and the estimator stays consistent. Switching techniques off makes the same code one
// of stage 6's methods: --mode bpt (no merges), ppm (merges and the light the camera hits), lt
// (only light tracing); in --mode vcm the first iteration chooses which the rest run.
#pragma once

#include "05-path-tracing/path_render.h"
#include "05-path-tracing/path_tracer.h"
#include "06-light-transport/bdpt.h"
#include "06-light-transport/photon_grid.h"
#include "07-vcm-mlt/vcm_budget.h"
#include "07-vcm-mlt/vcm_weight.h"
#include "common/memory_limit.h"
#include "common/progress.h"
#include "common/sample_sums.h"

#include <optional>

namespace rt {

enum class VcmMode { vcm, bpt, ppm, lt };
inline constexpr VcmMode kVcmModes[] = {VcmMode::vcm, VcmMode::bpt, VcmMode::ppm, VcmMode::lt};
const char* mode_name(VcmMode mode);  // vcm, bpt, ppm, lt
VcmTechniques techniques_of(VcmMode mode);

struct VcmOptions {
  VcmMode mode = VcmMode::vcm;
  // r_1 in scene units; 0: kVcmFootprintRadii pixel footprints at the median distance of the
  // camera's first hits (default_merge_radius).
  float initial_radius = 0.0f;
  float alpha = 0.75f;  // the radius's shrink exponent; SPPM's alpha, as Knaus & Zwicker show
  // The camera subpaths' numbers: stage 5's scrambled Sobol points, each pixel's camera samples
  // taking its points in order, so that the iterations stratify its area, its next-event light points and
  // its first bounces as stage 5's path tracer does; or independent numbers, as stage 6's BDPT
  // draws them. The light subpaths are shared by all pixels and stay independent.
  SamplerKind camera_sampler = SamplerKind::sobol;
  // --mode vcm: every iteration's budget; none: the first runs kEveryTechnique and chooses the
  // rest's (vcm_budget.h). The other modes run kEveryTechnique, less what they leave out.
  std::optional<VcmBudget> budget;
  int max_light_paths = 8;  // the most light subpaths per pixel the memory holds (check_vcm_fits)
  WalkSettings walk;
};

// The radius of iteration i = 1, 2, ...: r_1 i^((alpha - 1) / 2).
float merge_radius(float initial_radius, int iteration, float alpha);

// r_1 when none is given, in pixel footprints: merges then blur about what the pixels resolve.
inline constexpr float kVcmFootprintRadii = 1.0f;
float default_merge_radius(const LightingScene& scene, const Camera& camera);

// The densities of the full path that a connection (s, t) of the two subpaths makes (`sampled_light`
// replacing y_0 for s = 1), camera end first, those of the vertices at the connection recomputed
// for the joined path, as stage 6's mis_weight does; written to `out`, which must hold s + t.
std::span<const PathDensity> connection_densities(const LightingScene& scene, const Camera& camera,
                                                  std::span<const PathVertex> camera_path,
                                                  std::span<const PathVertex> light_path, int s, int t,
                                                  const PathVertex* sampled_light, std::span<PathDensity> out);
// The same for a merge of light vertex y_s-1 into camera vertex z_t-1 (s, t >= 2): the path of
// s + t - 1 vertices z_0 ... z_t-1 y_s-2 ... y_0, the connection (s - 1, t)'s, except that z_t-1
// was also sampled from the light side, with y_s-1's density (it lies within r of z_t-1); `out`
// must hold s + t - 1.
std::span<const PathDensity> merge_densities(const Camera& camera, std::span<const PathVertex> camera_path,
                                             std::span<const PathVertex> light_path, int s, int t,
                                             std::span<PathDensity> out);

// Task stage7.vcm.merge. What merging light vertex y = light_path[s - 1] into camera vertex
// z = camera_path[t - 1] adds, unweighted: beta(z) f(z) beta(y) / eta, f the scattering at z
// (stage 6's `scattering`) from y's incoming direction towards z_t-2. Zero where z or y is a delta
// vertex or where they lie on opposite sides of a surface (their normals facing apart: light on
// the back of a thin wall must not leak through it).
Color merge_contribution(std::span<const PathVertex> camera_path, std::span<const PathVertex> light_path, int s, int t,
                         float eta);

// The most light subpaths per pixel (1 or 8, vcm_budget.h) a render can hold within `limit`;
// throws InputError, before the scene is built, for a render that could not hold one: every
// stage's kBytesPerPixel and, per light subpath per pixel, an iteration's light subpaths (each
// vertex some 270 bytes with its BSDF), their photons and splats, measured as peak resident memory
// (/usr/bin/time, 128^2 and 512^2 pixels): 1.4 KiB a pixel in the Cornell box, 2.1 in the closed
// bright room of light-through-gap.json (longer subpaths), 0.75 in the caustic scene; 2.5 KiB
// covers them. The first iteration, with one light subpath a pixel, also holds what its choice
// reads: each pixel's second moments (kPixelMoments doubles, 288 bytes) and each splat's terms
// (BudgetTerms, 152 bytes; up to 5 splats a pixel, in the door-ajar scene), some 1.1 KiB a pixel.
inline constexpr std::uint64_t kVcmBytesPerPixel = 2560;
inline constexpr std::uint64_t kVcmChoiceBytesPerPixel = 1280;
int check_vcm_fits(const SceneDescription& description, const RenderSettings& settings, const MemoryLimit& limit);

// Per pixel of the image: the sum over the finished iterations of each one's estimate (its camera
// samples' mean, their merges included, and the light-tracing splats landing there), and their number. The same bit for
// bit for any thread count: light subpaths are traced in fixed chunks, their splats and photons
// taken in chunk order, and the grid visited in its fixed order. A stop request ends it between
// iterations (one cut short is dropped). The box filter only (a splat lands in one pixel). With
// `choice`, what the first iteration measured and chose.
SampleSums render_vcm(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                      const VcmOptions& options, int threads, SampleGuard& guard, ProgressBar* progress = nullptr,
                      VcmChoice* choice = nullptr);

}  // namespace rt
