#include "05-path-tracing/path_render.h"

#include "05-path-tracing/sobol_sampler.h"

namespace rt {

const char* integrator_name(PathIntegrator integrator) {
  switch (integrator) {
    case PathIntegrator::naive: return "naive";
    case PathIntegrator::russian_roulette: return "rr";
    case PathIntegrator::next_event_estimation:
      return "nee";
    case PathIntegrator::mis: return "mis";
  }
  return "?";
}

const char* sampler_name(SamplerKind sampler) { return sampler == SamplerKind::sobol ? "sobol" : "independent"; }

std::vector<std::pair<std::string, SamplerKind>> sampler_words() {
  std::vector<std::pair<std::string, SamplerKind>> words;
  for (const SamplerKind sampler : {SamplerKind::independent, SamplerKind::sobol})
    words.emplace_back(sampler_name(sampler), sampler);
  return words;
}

SampleSums render_path_samples(const LightingScene& scene, const Camera& camera,
                               const RenderSettings& settings, const PathOptions& options, SamplerKind sampler,
                               int threads, SampleGuard& guard, ProgressBar* progress,
                               const AdaptiveSettings* adaptive) {
  // `auto&`: each sampler's own path_radiance, with its calls compiled in.
  auto radiance = [&](const Ray& ray, auto& numbers) { return guard(path_radiance(scene, ray, options, numbers)); };
  if (adaptive) {
    if (sampler == SamplerKind::sobol)
      return render_adaptive<SobolSampler>(camera, settings, *adaptive, threads, radiance, progress);
    return render_adaptive<Rng>(camera, settings, *adaptive, threads, radiance, progress);
  }
  if (sampler == SamplerKind::sobol) return render_samples<SobolSampler>(camera, settings, threads, radiance, progress);
  return render_samples<Rng>(camera, settings, threads, radiance, progress);
}

Image render_paths(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                   const PathOptions& options, SamplerKind sampler, int threads, SampleGuard& guard,
                   ProgressBar* progress) {
  return render_path_samples(scene, camera, settings, options, sampler, threads, guard, progress).mean();
}

}  // namespace rt
