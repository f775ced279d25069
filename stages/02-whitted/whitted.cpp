#include "02-whitted/whitted.h"

#include "01-ray-casting/local_shading.h"
#include "common/emission.h"
#include "common/task.h"

namespace rt {

Color shade_direct(const WhittedScene& scene, const Hit& hit, Vec3 wo, const OffsetPolicy& offset) {
  const Material& material = scene.materials()[size_t(hit.material)];
  Color radiance(0.0f);
  // BEGIN TASK stage2.whitted.direct
  const Color albedo = material.albedo_at(hit.point);
  const Vec3 n = hit.shading_normal;
  for (const PointLight& light : scene.lights()) {
    const Vec3 to_light = light.position - hit.point;
    const float distance_squared = glm::dot(to_light, to_light);
    const Vec3 wi = to_light / std::sqrt(distance_squared);
    const float cos_theta = glm::dot(n, wi);
    // Behind the shading normal, or behind the geometric surface itself.
    if (cos_theta <= 0.0f || glm::dot(hit.normal, wi) <= 0.0f) continue;
    const ShadowRay shadow = spawn_shadow_ray(hit, light.position, offset);
    if (scene.occluded(shadow.ray, shadow.range)) continue;
    radiance += blinn_phong_brdf(material, albedo, n, wo, wi) * light.intensity * (cos_theta / distance_squared);
  }
  // PLACEHOLDER
  // report_unfinished_task("stage2.whitted.direct");
  // (void)wo, (void)offset;
  // radiance = material.albedo_at(hit.point) * 0.5f;  // flat colour: shapes stay visible
  // END TASK
  return radiance;
}

namespace {

// Whether a branch of this weight is worth following (WhittedOptions::min_weight).
[[maybe_unused]] bool worth_following(float weight, const WhittedOptions& options) {
  return weight >= options.min_weight && weight > 0.0f;
}

Color trace_mirror(const WhittedScene& scene, const Ray& ray, const Hit& hit, const Material& material,
                   const WhittedOptions& options, int depth, float weight) {
  // BEGIN TASK stage2.whitted.mirror
  const float reflected_weight = weight * max_component(material.reflectance);
  if (!worth_following(reflected_weight, options)) return Color(0.0f);
  const Vec3 reflected = reflect(ray.direction, hit.shading_normal);
  return material.reflectance * whitted_radiance(scene, spawn_ray(hit, reflected, options.offset), options,
                                                 depth + 1, reflected_weight);
  // PLACEHOLDER
  // report_unfinished_task("stage2.whitted.mirror");
  // (void)scene, (void)ray, (void)hit, (void)options, (void)depth, (void)weight;
  // return material.reflectance * 0.5f;
  // END TASK
}

// Light passing from one medium into another changes its radiance by (eta_t / eta_i)^2; a ray that
// enters and then leaves the glass picks up both factors, which cancel, so they are left out
// (Veach's thesis, section 5.2, has the general rule for non-symmetric transport).
Color trace_dielectric(const WhittedScene& scene, const Ray& ray, const Hit& hit, const Material& material,
                       const WhittedOptions& options, int depth, float weight) {
  // BEGIN TASK stage2.whitted.dielectric
  // hit.normal faces the incoming ray, so front_face says which side the ray comes from; the
  // material's index is inside, 1 outside (no nested media).
  const bool entering = hit.front_face;
  const float eta_i = entering ? 1.0f : material.ior;
  const float eta_t = entering ? material.ior : 1.0f;
  const Vec3 n = hit.shading_normal;
  const float cos_i = -glm::dot(ray.direction, n);
  const float reflectance = fresnel(options.fresnel, cos_i, eta_i, eta_t);
  Color radiance(0.0f);
  if (worth_following(weight * reflectance, options)) {
    const Vec3 reflected = reflect(ray.direction, n);
    radiance += reflectance * whitted_radiance(scene, spawn_ray(hit, reflected, options.offset), options,
                                               depth + 1, weight * reflectance);
  }
  if (worth_following(weight * (1.0f - reflectance), options))
    if (const std::optional<Vec3> refracted = refract(ray.direction, n, eta_i, eta_t))
      radiance += (1.0f - reflectance) * whitted_radiance(scene, spawn_ray(hit, *refracted, options.offset),
                                                          options, depth + 1, weight * (1.0f - reflectance));
  return radiance;
  // PLACEHOLDER
  // report_unfinished_task("stage2.whitted.dielectric");
  // (void)scene, (void)ray, (void)hit, (void)material, (void)options, (void)depth, (void)weight;
  // return Color(0.5f);
  // END TASK
}

}  // namespace

Color whitted_radiance(const WhittedScene& scene, const Ray& ray, const WhittedOptions& options, int depth,
                       float weight) {
  const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
  if (!hit) return scene.background();
  const Material& material = scene.materials()[size_t(hit->material)];
  const Color emitted = front_side_emission(material, *hit);
  switch (material.type) {
    case MaterialType::diffuse:
      return emitted + shade_direct(scene, *hit, -ray.direction, options.offset);
    case MaterialType::mirror:
      if (depth >= options.max_depth) return emitted;
      return emitted + trace_mirror(scene, ray, *hit, material, options, depth, weight);
    case MaterialType::dielectric:
      if (depth >= options.max_depth) return emitted;
      return emitted + trace_dielectric(scene, ray, *hit, material, options, depth, weight);
    case MaterialType::phong:
    case MaterialType::microfacet:
      break;  // refused by WhittedScene's constructor
  }
  return emitted;
}

Color whitted_debug(const WhittedScene& scene, const Ray& ray, DebugView view) {
  const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
  if (!hit) return Color(0.0f);
  return debug_color(*hit, scene.materials()[size_t(hit->material)], view);
}

}  // namespace rt
