#include "04-radiometry/direct_lighting.h"

#include "04-radiometry/radiometry.h"
#include "04-radiometry/warp.h"
#include "common/task.h"

namespace rt {

namespace {

// Le arriving at the shading point along the world direction wi: the front-face emission of the
// first surface a ray in that direction hits, or the environment's radiance if it escapes (stage 4
// is direct light only).
[[maybe_unused]] Color emitted_along(const LightingScene& scene, const ShadingPoint& at, Vec3 wi, const OffsetPolicy& offset) {
  const std::optional<Hit> hit = scene.closest_hit(spawn_ray(at.hit, wi, offset), Interval::positive());
  return hit ? scene.emitted(*hit) : scene.environment_radiance(wi);
}

}  // namespace

Color direct_from_point_lights(const LightingScene& scene, const ShadingPoint& at, const OffsetPolicy& offset) {
  // BEGIN TASK stage4.direct.point_lights
  Color sum(0.0f);
  for (const PointLight& light : scene.lights()) {
    const Vec3 to_light = light.position - at.hit.point;
    const float distance = glm::length(to_light);
    if (!(distance > 0.0f)) continue;
    const Vec3 wi = at.frame.to_local(to_light / distance);
    const Color f = at.bsdf.eval(at.wo, wi);
    if (f == Color(0.0f)) continue;
    const ShadowRay shadow = spawn_shadow_ray(at.hit, light.position, offset);
    if (scene.occluded(shadow.ray, shadow.range)) continue;
    sum += f * point_light_irradiance(light.intensity, distance, wi.z);
  }
  return sum;
  // PLACEHOLDER
  // report_unfinished_task("stage4.direct.point_lights");
  // (void)scene, (void)at, (void)offset;
  // return Color(0.0f);
  // END TASK
}

Color direct_by_hemisphere(const LightingScene& scene, const ShadingPoint& at, bool cosine, Sampler& rng,
                           const OffsetPolicy& offset) {
  // BEGIN TASK stage4.direct.hemisphere
  const Vec2 u = rng.uniform2();
  const Vec3 wi = cosine ? sample_cosine_hemisphere(u) : sample_uniform_hemisphere(u);
  const float pdf = cosine ? cosine_hemisphere_pdf(wi) : uniform_hemisphere_pdf(wi);
  const Color f = at.bsdf.eval(at.wo, wi);
  if (!(pdf > 0.0f) || f == Color(0.0f)) return Color(0.0f);
  return f * emitted_along(scene, at, at.frame.to_world(wi), offset) * (wi.z / pdf);
  // PLACEHOLDER
  // report_unfinished_task("stage4.direct.hemisphere");
  // (void)scene, (void)at, (void)cosine, (void)rng, (void)offset;
  // return Color(0.0f);
  // END TASK
}

Color direct_by_brdf_sampling(const LightingScene& scene, const ShadingPoint& at, Sampler& rng, const OffsetPolicy& offset) {
  // BEGIN TASK stage4.direct.brdf_sampling
  const Vec2 u = rng.uniform2();
  const std::optional<BsdfSample> s = at.bsdf.sample(at.wo, u, rng.uniform());
  if (!s) return Color(0.0f);
  return s->weight * emitted_along(scene, at, at.frame.to_world(s->wi), offset);
  // PLACEHOLDER
  // report_unfinished_task("stage4.direct.brdf_sampling");
  // (void)scene, (void)at, (void)rng, (void)offset;
  // return Color(0.0f);
  // END TASK
}

DirectLightSample sample_direct_light(const LightingScene& scene, const ShadingPoint& at, float u_choice, Vec2 u,
                                      const OffsetPolicy& offset) {
  if (scene.emitter_distribution().empty()) return {};
  // BEGIN TASK stage4.direct.light_sampling
  const DiscreteDistribution::Choice choice = scene.emitter_distribution().sample(u_choice);
  if (choice.index == scene.environment_index()) {
    // The environment: a direction, and a shadow ray that must escape the scene to see it.
    const std::optional<EnvironmentSample> s = scene.environment()->sample(u);
    if (!s) return {};
    DirectLightSample result;
    result.wi = at.frame.to_local(s->wi);
    result.pdf = choice.pmf * s->pdf;
    const Color f = at.bsdf.eval(at.wo, result.wi);
    if (f == Color(0.0f) || scene.occluded(spawn_ray(at.hit, s->wi, offset), Interval::positive())) return result;
    result.value = f * s->radiance * (result.wi.z / result.pdf);
    return result;
  }
  const AreaEmitter& emitter = scene.emitters()[size_t(choice.index)];
  const EmitterSample s = emitter.sample(at.hit.point, u);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return {};
  DirectLightSample result;
  result.wi = at.frame.to_local(s.wi);
  result.pdf = choice.pmf * s.pdf;
  const Color le = emitter.radiance_towards(s.point, at.hit.point);
  const Color f = at.bsdf.eval(at.wo, result.wi);
  if (le == Color(0.0f) || f == Color(0.0f)) return result;
  const ShadowRay shadow = spawn_shadow_ray(at.hit, s.point, offset);
  if (scene.occluded(shadow.ray, shadow.range)) return result;
  result.value = f * le * (result.wi.z / result.pdf);
  return result;
  // PLACEHOLDER
  // report_unfinished_task("stage4.direct.light_sampling");
  // (void)at, (void)offset, (void)u_choice, (void)u;
  // return {};
  // END TASK
}

Color direct_radiance(const LightingScene& scene, const Ray& ray, const DirectOptions& options, Sampler& rng, int depth) {
  const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
  if (!hit) return scene.escaped_radiance(ray.direction);
  const Color emitted = scene.emitted(*hit);
  const ShadingPoint at = make_shading_point(scene, *hit, -ray.direction);

  if (at.bsdf.is_delta()) {
    if (depth >= options.max_depth) return emitted;
    const Vec2 u = rng.uniform2();
    const std::optional<BsdfSample> s = at.bsdf.sample(at.wo, u, rng.uniform());
    if (!s) return emitted;
    const Ray next = spawn_ray(*hit, at.frame.to_world(s->wi), options.offset);
    return emitted + s->weight * direct_radiance(scene, next, options, rng, depth + 1);
  }

  Color reflected = direct_from_point_lights(scene, at, options.offset);
  switch (options.estimator) {
    case DirectEstimator::uniform_hemisphere:
      reflected += direct_by_hemisphere(scene, at, false, rng, options.offset);
      break;
    case DirectEstimator::cosine_hemisphere:
      reflected += direct_by_hemisphere(scene, at, true, rng, options.offset);
      break;
    case DirectEstimator::brdf:
      reflected += direct_by_brdf_sampling(scene, at, rng, options.offset);
      break;
    case DirectEstimator::light:
      reflected += direct_by_light_sampling(scene, at, rng, options.offset);
      break;
  }
  return emitted + reflected;
}

}  // namespace rt
