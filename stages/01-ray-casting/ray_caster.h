// Stage 1: what one camera ray sees: the locally shaded surface, or one of the debug views
// (normals, depth, albedo) that make a wrong intersection obvious at a glance.
#pragma once

#include "01-ray-casting/ray_casting_scene.h"
#include "common/program.h"

#include <string>

namespace rt {

enum class DebugView {
  none,    // local shading (local_shading.h)
  normal,  // outward unit normal n mapped to colour (n + 1) / 2; black where nothing is hit
  depth,   // distance t to the hit in scene units (0 where nothing is hit)
  albedo,  // the material's diffuse reflectance
};

// "normal" -> DebugView::normal and so on; throws UsageError for an unknown name.
DebugView debug_view_from_name(const std::string& name);
// What a view's pixels hold, for the program shell (common/program.h): distances for depth.
inline PixelMeaning meaning_of(DebugView view) {
  return view == DebugView::depth ? PixelMeaning::depth : PixelMeaning::radiance;
}

Color cast_ray(const RayCastingScene& scene, const Ray& ray, DebugView view = DebugView::none);

// The colour of a debug view (not DebugView::none) at a hit, for this stage and the later ones.
// The normal view shows the outward shading normal.
Color debug_color(const Hit& hit, const Material& material, DebugView view);

}  // namespace rt
