#include "01-ray-casting/local_shading.h"

#include "common/emission.h"
#include "common/task.h"

#include <cmath>

namespace rt {

Color blinn_phong_brdf(const Material& material, Color albedo, Vec3 n, Vec3 wo, Vec3 wi) {
  // BEGIN TASK stage1.shading.brdf
  const Color diffuse = albedo * kInvPi;
  if (material.specular == Color(0.0f)) return diffuse;
  const Vec3 half_vector = glm::normalize(wi + wo);
  const float cos_h = std::max(0.0f, glm::dot(n, half_vector));
  const float lobe = (material.shininess + 8.0f) / (8.0f * kPi) * std::pow(cos_h, material.shininess);
  return diffuse + material.specular * lobe;
  // PLACEHOLDER
  // report_unfinished_task("stage1.shading.brdf");
  // (void)n, (void)wi, (void)wo;
  // (void)material;
  // return albedo * kInvPi;
  // END TASK
}

Color shade_local(const RayCastingScene& scene, const Hit& hit, Vec3 to_viewer) {
  const Material& material = scene.materials()[size_t(hit.material)];
  Color radiance = front_side_emission(material, hit);
  // BEGIN TASK stage1.shading.local
  const Color albedo = material.albedo_at(hit.point);
  const Vec3 shadow_origin = hit.point + kShadowRayOffset * hit.normal;
  for (const PointLight& light : scene.lights()) {
    const Vec3 to_light = light.position - hit.point;
    const float distance_squared = glm::dot(to_light, to_light);
    const float distance = std::sqrt(distance_squared);
    const Vec3 wi = to_light / distance;
    const float cos_theta = glm::dot(hit.normal, wi);
    if (cos_theta <= 0.0f) continue;  // the light is behind the surface
    const Vec3 shadow_span = light.position - shadow_origin;
    const float shadow_length = glm::length(shadow_span);
    if (scene.occluded(Ray{shadow_origin, shadow_span / shadow_length}, Interval{0.0f, shadow_length}))
      continue;
    radiance += blinn_phong_brdf(material, albedo, hit.normal, to_viewer, wi) * light.intensity *
                (cos_theta / distance_squared);
  }
  // PLACEHOLDER
  // report_unfinished_task("stage1.shading.local");
  // (void)to_viewer;
  // radiance += material.albedo_at(hit.point) * 0.5f;  // flat colour: shapes stay visible
  // END TASK
  return radiance;
}

}  // namespace rt
