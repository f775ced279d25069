#include "01-ray-casting/ray_caster.h"
#include "01-ray-casting/render.h"
#include "common/metrics.h"

#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::subject;

// Camera at the origin looking down +z; a unit sphere 5 ahead, a smaller one up and to +x.
SceneDescription two_spheres() {
  return parse_scene(R"({
    "render": {"width": 48, "height": 32, "spp": 4, "seed": 11},
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "vfov": 50},
    "background": [0.1, 0.2, 0.3],
    "materials": {"white": {"albedo": [1, 1, 1]}, "red": {"albedo": [1, 0, 0], "specular": [0.5, 0.5, 0.5]}},
    "shapes": [
      {"type": "sphere", "center": [0, 0, 5], "radius": 1, "material": "white"},
      {"type": "sphere", "center": [1.6, 1.2, 5], "radius": 0.5, "material": "red"}
    ],
    "lights": [{"type": "point", "position": [0, 3, 0], "intensity": [20, 20, 20]}]
  })", "two-spheres");
}

Image render(const SceneDescription& d, const RenderSettings& settings, int threads,
             DebugView view = DebugView::none) {
  const RayCastingScene scene(d);
  const Camera camera(d.camera, settings.width, settings.height);
  return subject([&] {
    return render_image(camera, settings, threads, [&](const Ray& ray, Rng&) { return cast_ray(scene, ray, view); });
  });
}

TEST(Render, BitIdenticalForAnyThreadCount) {
  const SceneDescription d = two_spheres();
  const Image one = render(d, d.render, 1);
  EXPECT_EQ(render(d, d.render, 2), one);
  EXPECT_EQ(render(d, d.render, 5), one);
}

TEST(Render, SeedChangesOnlyTheNoise) {
  const SceneDescription d = two_spheres();
  RenderSettings other = d.render;
  other.seed = 12;
  const Image a = render(d, d.render, 2), b = render(d, other, 2);
  EXPECT_NE(a, b) << "pixels on silhouettes depend on where the samples fall";
  EXPECT_LT(rmse(a, b), 0.05) << "but the image is the same picture";
}

TEST(Render, PixelCentreOnlyIsOneRayPerPixel) {
  const SceneDescription d = two_spheres();
  RenderSettings centre = d.render;
  centre.pixel_center_only = true;
  RenderSettings single = centre;
  single.spp = 1;
  EXPECT_EQ(render(d, centre, 2), render(d, single, 2));
}

TEST(Render, ImageOrientation) {
  // Row 0 is the top of the image, and +x world is on the LEFT for this camera (docs/design.md):
  // the red sphere at (+1.6, +1.2) lands in the top-left quarter.
  const SceneDescription d = two_spheres();
  RenderSettings s = d.render;
  s.pixel_center_only = true;
  const Image albedo = render(d, s, 1, DebugView::albedo);
  int red_left_top = 0, red_elsewhere = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      if (albedo.at(x, y) == Color(1, 0, 0)) (x < s.width / 2 && y < s.height / 2 ? red_left_top : red_elsewhere)++;
  EXPECT_GT(red_left_top, 5);
  EXPECT_EQ(red_elsewhere, 0);
}

TEST(Render, DebugViewsAtTheImageCentre) {
  // 2 x 2 pixels, centre-only: the pixel centres are just off the axis, so use a 1 x 1 image.
  const SceneDescription d = two_spheres();
  RenderSettings s = d.render;
  s.width = s.height = 1;
  s.pixel_center_only = true;
  const Color normal = render(d, s, 1, DebugView::normal).at(0, 0);
  EXPECT_NEAR(normal.r, 0.5f, 1e-6f);
  EXPECT_NEAR(normal.g, 0.5f, 1e-6f);
  EXPECT_NEAR(normal.b, 0.0f, 1e-6f) << "outward normal (0, 0, -1) maps to (0.5, 0.5, 0)";
  EXPECT_NEAR(render(d, s, 1, DebugView::depth).at(0, 0).r, 4.0f, 1e-5f);
  EXPECT_EQ(render(d, s, 1, DebugView::albedo).at(0, 0), Color(1.0f));
}

TEST(Render, MissesSeeTheBackground) {
  SceneDescription d = two_spheres();
  d.camera.look_at = Vec3(0, 0, -1);  // looking away from everything
  const Image image = render(d, d.render, 2);
  for (const Color& c : image.pixels()) ASSERT_EQ(c, Color(0.1f, 0.2f, 0.3f));
}

TEST(Render, PixelValueIsTheMeanOfItsSamples) {
  // With a radiance that is the sample's film position, the pixel mean must be the pixel
  // centre's position to within the sampling error of a uniform mean (1/sqrt(12 N) per axis).
  const SceneDescription d = two_spheres();
  RenderSettings s = d.render;
  s.width = 4;
  s.height = 4;
  s.spp = 4096;
  const Camera camera(d.camera, s.width, s.height);
  const Image image = subject([&] {
    return render_image(camera, s, 2, [&](const Ray& ray, Rng&) {
      return Color(ray.direction.x / ray.direction.z, ray.direction.y / ray.direction.z, 0.0f);
    });
  });
  const float pixel_size = 2.0f * camera.tan_half_vfov / float(s.height);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const Ray centre = subject([&] { return generate_camera_ray(camera, Vec2(x + 0.5f, y + 0.5f)); });
      const float sigma = pixel_size / std::sqrt(12.0f * float(s.spp));
      EXPECT_NEAR(image.at(x, y).r, centre.direction.x / centre.direction.z, 5.0f * sigma);
      EXPECT_NEAR(image.at(x, y).g, centre.direction.y / centre.direction.z, 5.0f * sigma);
    }
}

TEST(Render, SampleBatchesAreTheWholeRendersSamples) {
  // Samples [2, 5) rendered apart are samples 2, 3 and 4 of the whole render: with a radiance
  // that is the sample's film position, each batch's sum is the whole render's sum of the same
  // samples, bit for bit (so batches rendered on other machines add up: docs/scale-out.md).
  const SceneDescription d = two_spheres();
  RenderSettings s = d.render;
  s.width = 6;
  s.height = 4;
  const Camera camera(d.camera, s.width, s.height);
  const auto position = [](const Ray& ray, Rng&) { return Color(ray.direction.x, ray.direction.y, 0.0f); };
  const auto sums = [&](int first, int spp) {
    RenderSettings batch = s;
    batch.first_sample = first;
    batch.spp = spp;
    return subject([&] { return render_samples(camera, batch, 1, position); });
  };
  const SampleSums whole = sums(0, 5), first = sums(0, 2), rest = sums(2, 3);
  const SampleSums one_by_one[] = {sums(2, 1), sums(3, 1), sums(4, 1)};
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      // The whole render adds its samples in order 0..4, so its sum is (first + sample 2) + 3 + 4.
      Color expected = first.sum(x, y);
      for (const SampleSums& one : one_by_one) expected += one.sum(x, y);
      EXPECT_EQ(whole.sum(x, y), expected) << "pixel " << x << ", " << y;
      EXPECT_EQ(rest.sum(x, y), one_by_one[0].sum(x, y) + one_by_one[1].sum(x, y) + one_by_one[2].sum(x, y));
      EXPECT_EQ(rest.count(x, y), 3u);
    }
}

TEST(Render, SpheresSceneHasNoNanAndLightsSomething) {
  const SceneDescription d = load_scene(testing::source_path("assets/scenes/spheres.json"));
  RenderSettings s = d.render;
  s.width = 160;
  s.height = 100;
  s.spp = 1;
  const Image image = render(d, s, 2);
  float brightest = 0.0f;
  for (const Color& c : image.pixels()) {
    ASSERT_TRUE(is_finite(c));
    brightest = std::max(brightest, max_component(c));
  }
  EXPECT_GT(brightest, 0.5f);
}

}  // namespace
}  // namespace rt
