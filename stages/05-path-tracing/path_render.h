// Stage 5: a whole image by path tracing: stage 1's pixel loop (a box filter over each pixel) with
// the integrator's radiance, each sample's numbers from the chosen sampler. Shared by the program,
// the tests and the benchmarks, so all three render the same way.
#pragma once

#include "01-ray-casting/render.h"
#include "05-path-tracing/adaptive_sampling.h"
#include "05-path-tracing/path_tracer.h"

#include <string>
#include <utility>
#include <vector>

namespace rt {

enum class SamplerKind { independent, sobol };

// Every integrator, in the lecture's order, and its name as the program's flag spells it.
inline constexpr PathIntegrator kPathIntegrators[] = {PathIntegrator::naive, PathIntegrator::russian_roulette,
                                                      PathIntegrator::next_event_estimation, PathIntegrator::mis};
const char* integrator_name(PathIntegrator integrator);  // naive, rr, nee, mis
const char* sampler_name(SamplerKind sampler);           // independent, sobol
// Each sampler with its name, for a program's --sampler flag (stage5's, and stage7's camera subpaths).
std::vector<std::pair<std::string, SamplerKind>> sampler_words();

// The image of `settings.spp` paths per pixel. Samples with NaN, infinite or negative radiance are
// counted by `guard` and enter the image as black. Deterministic for any thread count.
Image render_paths(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                   const PathOptions& options, SamplerKind sampler, int threads, SampleGuard& guard,
                   ProgressBar* progress = nullptr);
// The same undivided, per pixel the sum and number of its paths (stage 1's render_samples), for a
// program that writes sample batches. With `adaptive`, each pixel stops when its estimate is good
// enough (adaptive_sampling.h), at most settings.spp paths.
SampleSums render_path_samples(const LightingScene& scene, const Camera& camera,
                               const RenderSettings& settings, const PathOptions& options, SamplerKind sampler,
                               int threads, SampleGuard& guard, ProgressBar* progress = nullptr,
                               const AdaptiveSettings* adaptive = nullptr);

}  // namespace rt
