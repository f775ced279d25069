#include "01-ray-casting/ray_caster.h"

#include "01-ray-casting/local_shading.h"
#include "common/error.h"

namespace rt {

DebugView debug_view_from_name(const std::string& name) {
  if (name == "none") return DebugView::none;
  if (name == "normal") return DebugView::normal;
  if (name == "depth") return DebugView::depth;
  if (name == "albedo") return DebugView::albedo;
  throw UsageError("unknown debug view '" + name + "' (known: none, normal, depth, albedo)");
}

Color cast_ray(const RayCastingScene& scene, const Ray& ray, DebugView view) {
  const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
  if (!hit) return view == DebugView::none ? scene.background() : Color(0.0f);
  const Material& material = scene.materials()[size_t(hit->material)];
  return view == DebugView::none ? shade_local(scene, *hit, -ray.direction) : debug_color(*hit, material, view);
}

Color debug_color(const Hit& hit, const Material& material, DebugView view) {
  switch (view) {
    case DebugView::normal: {
      const Vec3 outward = hit.front_face ? hit.shading_normal : -hit.shading_normal;
      return 0.5f * (outward + 1.0f);
    }
    case DebugView::depth:
      return Color(hit.t);
    case DebugView::albedo:
      return material.albedo_at(hit.point);
    case DebugView::none:
      break;
  }
  return Color(0.0f);
}

}  // namespace rt
