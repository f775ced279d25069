#include "05-path-tracing/path_tracer.h"

#include "05-path-tracing/sobol_sampler.h"
#include "common/task.h"

namespace rt {

float survival_probability(Color beta) {
  // BEGIN TASK stage5.path.russian_roulette
  return std::min(0.95f, max_component(beta));
  // PLACEHOLDER
  // report_unfinished_task("stage5.path.russian_roulette");
  // (void)beta;
  // return 0.95f;
  // END TASK
}

float power_heuristic(float pdf_a, float pdf_b) {
  // BEGIN TASK stage5.path.mis_weight
  if (std::isinf(pdf_a)) return 1.0f;
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
  // PLACEHOLDER
  // report_unfinished_task("stage5.path.mis_weight");
  // (void)pdf_a, (void)pdf_b;
  // return 0.5f;
  // END TASK
}

float light_sampling_pdf(const LightingScene& scene, Vec3 from, const Hit& hit) {
  const int index = scene.emitter_index(hit);
  if (index < 0) return 0.0f;
  return scene.emitter_distribution().pmf(index) * scene.emitters()[size_t(index)].pdf(from, hit.point);
}

float environment_sampling_pdf(const LightingScene& scene, Vec3 direction) {
  const EnvironmentLight* environment = scene.environment();
  if (!environment) return 0.0f;
  return scene.emitter_distribution().pmf(scene.environment_index()) * environment->pdf(direction);
}

template <SamplerType S>
Color path_radiance(const LightingScene& scene, const Ray& camera_ray, const PathOptions& options, S& sampler) {
  const PathIntegrator integrator = options.integrator;
  const bool samples_lights = integrator == PathIntegrator::next_event_estimation || integrator == PathIntegrator::mis;
  Color radiance(0.0f), beta(1.0f);
  Ray ray = camera_ray;
  // What the previous bounce was: a delta lobe (or the camera), and the density it sampled with.
  bool after_delta = true;
  float bsdf_pdf = 0.0f;
  Vec3 previous_point(0.0f);

  for (int bounce = 0;; ++bounce) {
    // This bounce's direction numbers, drawn before the ray is traced: docs/stage5.md, ladder step 17.
    const Vec2 u = sampler.uniform2();
    const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
    if (!hit) {
      // BEGIN TASK stage5.path.environment
      // The environment, found by the path leaving the scene: the same rule as for an emitter it
      // hits, with the environment's density. A background lights nothing and no light sample
      // finds it, so the path counts it whole.
      if (const EnvironmentLight* environment = scene.environment()) {
        const Color le = environment->radiance(ray.direction);
        if (!samples_lights || after_delta) {
          radiance += beta * le;
        } else if (integrator == PathIntegrator::mis) {
          radiance += beta * le * power_heuristic(bsdf_pdf, environment_sampling_pdf(scene, ray.direction));
        }
      } else {
        radiance += beta * scene.background();
      }
      // PLACEHOLDER
      // report_unfinished_task("stage5.path.environment");
      // radiance += beta * scene.escaped_radiance(ray.direction);
      // END TASK
      break;
    }
    // BEGIN TASK stage5.path.emitted
    // Emitted light found by the path itself. With light sampling, the previous vertex already
    // counted it (unless it was a delta lobe, which light sampling cannot serve); with MIS, both
    // counted it, each with its weight.
    const Color le = scene.emitted(*hit);
    if (le != Color(0.0f)) {
      if (!samples_lights || after_delta) {
        radiance += beta * le;
      } else if (integrator == PathIntegrator::mis) {
        const float w = power_heuristic(bsdf_pdf, light_sampling_pdf(scene, previous_point, *hit));
        radiance += beta * le * w;
      }
    }
    // PLACEHOLDER
    // report_unfinished_task("stage5.path.emitted");
    // const Color le = scene.emitted(*hit);
    // if (!samples_lights || after_delta) radiance += beta * le;
    // (void)bsdf_pdf, (void)previous_point;  // what the MIS weight needs
    // END TASK
    if (integrator == PathIntegrator::naive ? bounce >= options.max_depth : bounce >= options.max_bounces) break;

    const ShadingPoint at = make_shading_point(scene, *hit, -ray.direction);
    // The direction is sampled before the light, though it is used only after it: the two do not
    // depend on each other, and sampled first, the direction's chain of dependent steps (a
    // division, polynomials, a square root) runs while the light sample is worked on, instead of
    // stalling at the end of the bounce (the speed ladder, step 11). A number to choose a lobe is
    // drawn only for a model that has more than one (step 15).
    const float u_lobe = at.bsdf.has_lobe_choice() ? sampler.uniform() : 0.5f;
    const std::optional<BsdfSample> s = at.bsdf.sample(at.wo, u, u_lobe);
    // BEGIN TASK stage5.path.next_event
    if (samples_lights && !at.bsdf.is_delta()) {
      const DirectLightSample light = sample_direct_light(scene, at, sampler, options.offset);
      const float w = integrator == PathIntegrator::mis ? power_heuristic(light.pdf, at.bsdf.pdf(at.wo, light.wi)) : 1.0f;
      radiance += beta * light.value * w;
    }
    // PLACEHOLDER
    // report_unfinished_task("stage5.path.next_event");
    // END TASK

    if (!s) break;
    beta *= s->weight;
    after_delta = s->delta;
    bsdf_pdf = s->pdf;
    previous_point = hit->point;
    ray = spawn_ray(*hit, at.frame.to_world(s->wi), options.offset);

    if (integrator != PathIntegrator::naive && bounce + 1 >= options.roulette_start) {
      const float p = survival_probability(beta);
      if (!(sampler.uniform() < p)) break;
      beta /= p;
    }
  }
  return radiance;
}

template Color path_radiance(const LightingScene&, const Ray&, const PathOptions&, Rng&);
template Color path_radiance(const LightingScene&, const Ray&, const PathOptions&, SobolSampler&);
template Color path_radiance(const LightingScene&, const Ray&, const PathOptions&, Sampler&);

}  // namespace rt
