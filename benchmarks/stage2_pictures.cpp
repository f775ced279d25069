// Renders the two failure pictures of docs/stage2.md, each a pair side by side:
//   docs/images/stage2-acne.png    the acne scene at scale 1e4: fixed epsilon 1e-4 | error bound
//   docs/images/stage2-cracks.png  a wall of triangles whose edges lie on pixel-centre rays, red
//                                  behind it: Moeller-Trumbore | watertight
// and prints how many pixels are wrong in each. Run through tools/make-charts.sh.
#include "01-ray-casting/render.h"
#include "experiments/acne_experiment.h"
#include "02-whitted/whitted.h"
#include "common/image_io.h"

#include <cstdio>

namespace rt {
namespace {

Image side_by_side(const Image& left, const Image& right) {
  Image both(left.width() + right.width() + 4, left.height());
  for (int y = 0; y < left.height(); ++y) {
    for (int x = 0; x < left.width(); ++x) both.at(x, y) = left.at(x, y);
    for (int x = 0; x < right.width(); ++x) both.at(left.width() + 4 + x, y) = right.at(x, y);
  }
  return both;
}

Image render_whitted(const SceneDescription& d, const WhittedOptions& options, TriangleMethod method) {
  const WhittedScene scene(d, method);
  RenderSettings settings = d.render;
  settings.spp = 1;
  settings.pixel_center_only = true;
  return render_image(Camera(d.camera, settings.width, settings.height), settings, 0,
                      [&](const Ray& ray, Rng&) { return whitted_radiance(scene, ray, options); });
}

// A wall of squares at z = 1, seen through a 90-degree camera at the origin, whose grid lines sit
// exactly where every other pixel-centre ray meets the wall: those rays pass within an ulp of an
// edge or a vertex shared by two triangles.
SceneDescription crack_wall(int size) {
  SceneDescription d;
  d.source = "crack wall";
  d.render.width = d.render.height = size;
  d.camera = CameraSpec{Vec3(0), Vec3(0, 0, 1), Vec3(0, 1, 0), 90.0f};
  d.background = Color(1, 0, 0);
  Material white;
  white.albedo = Color(0.0f);
  white.emission = Color(0.8f);
  d.materials = {white};
  auto line = [&](int k) { return (2.0f * (float(k) + 0.5f) / float(size) - 1.0f); };
  for (int i = 0; i + 2 < size; i += 2)
    for (int j = 0; j + 2 < size; j += 2) {
      const float x0 = -line(i), x1 = -line(i + 2), y0 = -line(j), y1 = -line(j + 2);  // +x is on the left
      // Corners in this order make the outward normal -z, towards the camera.
      d.shapes.push_back(Shape{"tile", Quad{{Vec3(x0, y0, 1), Vec3(x0, y1, 1), Vec3(x1, y1, 1), Vec3(x1, y0, 1)}}, 0});
    }
  return d;
}

// Background pixels inside the wall, away from its outer border (where a ray on the last grid
// line has no neighbouring triangle to catch it): rays that slipped through.
int count_cracks(const Image& image) {
  int n = 0;
  for (int y = 3; y < image.height() - 3; ++y)
    for (int x = 3; x < image.width() - 3; ++x) n += image.at(x, y) == Color(1, 0, 0) ? 1 : 0;
  return n;
}

}  // namespace
}  // namespace rt

int main(int argc, char** argv) {
  using namespace rt;
  const std::string root = argc > 1 ? argv[1] : ".";

  const SceneDescription acne = make_acne_scene(1e4f, 240, 180);
  WhittedOptions fixed, robust;
  fixed.offset = OffsetPolicy{OffsetMethod::fixed, 1e-4f};
  const Image with_fixed = render_whitted(acne, fixed, TriangleMethod::watertight);
  const Image with_bound = render_whitted(acne, robust, TriangleMethod::watertight);
  write_image(root + "/docs/images/stage2-acne.png", side_by_side(with_fixed, with_bound));
  std::printf("acne picture: scale 1e4, fixed epsilon 1e-4 | error bound\n");

  const SceneDescription wall = crack_wall(128);
  const WhittedOptions none;
  const Image mt = render_whitted(wall, none, TriangleMethod::moller_trumbore);
  const Image wt = render_whitted(wall, none, TriangleMethod::watertight);
  write_image(root + "/docs/images/stage2-cracks.png", side_by_side(mt, wt));
  std::printf("crack picture: %zu triangles, rays through the wall that hit nothing: Moller-Trumbore %d, "
              "watertight %d (of %d)\n", 2 * wall.shapes.size(), count_cracks(mt), count_cracks(wt), 122 * 122);
  return 0;
}
