#include "01-ray-casting/ray_casting_scene.h"

#include "01-ray-casting/plane_intersection.h"
#include "01-ray-casting/sphere_intersection.h"
#include "common/error.h"
#include "common/task.h"

namespace rt {

RayCastingScene::RayCastingScene(const SceneDescription& description)
    : materials_(description.materials),
      lights_(description.lights),
      background_(description.background) {
  for (size_t i = 0; i < description.shapes.size(); ++i) {
    const Shape& shape = description.shapes[i];
    const int index = int(i);
    if (const auto* sphere = std::get_if<Sphere>(&shape.geometry))
      spheres_.push_back({*sphere, shape.material, index});
    else if (const auto* plane = std::get_if<Plane>(&shape.geometry))
      planes_.push_back({*plane, shape.material, index});
    else if (const auto* torus = std::get_if<Torus>(&shape.geometry))
      tori_.push_back({TorusSurface(*torus), shape.material, index});
    else
      throw InputError(description.source + ": /shapes/" + std::to_string(i) +
                       ": stage 1 renders spheres, planes and tori only (triangles, quads and "
                       "meshes come with stage 2, disks with stage 4)");
  }
  for (const Material& material : materials_)
    if (material.type != MaterialType::diffuse)
      throw InputError(description.source + ": /materials/" + material.name +
                       ": stage 1 shades diffuse materials only (mirror and dielectric come with "
                       "stage 2, phong and microfacet with stage 4)");
}

std::optional<Hit> RayCastingScene::closest_hit(const Ray& ray, Interval range) const {
  // BEGIN TASK stage1.scene.closest_hit
  std::optional<Hit> closest;
  // The hit record (common/hit.h) of the nearest hit so far; later shapes count only when nearer.
  auto record = [&](float t, Vec3 outward_normal, int material, int shape) {
    closest = make_hit(ray, t, ray.at(t), Vec3(0.0f), outward_normal, material, shape);
    range.max = t;
  };
  for (const auto& s : spheres_)
    if (const auto t = intersect_sphere_stable(ray, s.geometry, range))
      record(*t, sphere_normal(s.geometry, ray.at(*t)), s.material, s.shape);
  for (const auto& p : planes_)
    if (const auto t = intersect_plane(ray, p.geometry, range))
      record(*t, p.geometry.normal, p.material, p.shape);
  for (const auto& torus : tori_)
    if (const auto hit = intersect_implicit(torus.geometry, ray, range))
      record(hit->t, glm::normalize(torus.geometry.gradient(ray.at(hit->t))), torus.material,
             torus.shape);
  return closest;
  // PLACEHOLDER
  // report_unfinished_task("stage1.scene.closest_hit");
  // (void)ray, (void)range;
  // return std::nullopt;
  // END TASK
}

bool RayCastingScene::occluded(const Ray& ray, Interval range) const {
  for (const auto& s : spheres_)
    if (intersect_sphere_stable(ray, s.geometry, range)) return true;
  for (const auto& p : planes_)
    if (intersect_plane(ray, p.geometry, range)) return true;
  for (const auto& torus : tori_)
    if (intersect_implicit(torus.geometry, ray, range)) return true;
  return false;
}

}  // namespace rt
