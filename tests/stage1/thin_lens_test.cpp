// Stage 1: the thin lens (camera_rays.h) and the concentric disk map it samples the lens with
// (disk_sampling.h). The circle of confusion is checked against the thin-lens formula at both sides
// of the focal plane, by finding, for each lens point, the film point that sees a given scene point.
#include "01-ray-casting/camera_rays.h"
#include "01-ray-casting/disk_sampling.h"
#include "01-ray-casting/render.h"
#include "common/random.h"
#include "support/chi_square.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using testing::subject;

// A general camera frame (not axis-aligned), 160 x 120 pixels, vfov 50 degrees, aperture 0.2,
// focused at 4 units.
CameraSpec lens_spec(float aperture, float focus) {
  CameraSpec spec{Vec3(1.0f, 2.0f, -3.0f), Vec3(1.5f, 1.8f, 1.0f), Vec3(0.1f, 1.0f, 0.0f), 50.0f};
  spec.aperture_radius = aperture;
  spec.focus_distance = focus;
  return spec;
}
const Camera kLens(lens_spec(0.2f, 4.0f), 160, 120);

// Pixels per unit of film at the film's distance 1: the film's height H spans 2 tan(vfov/2).
double pixels_per_film_unit(const Camera& c) { return double(c.height) / (2.0 * double(c.tan_half_vfov)); }

// Where the ray meets the plane at distance z along `forward`, in (right, up) coordinates relative
// to the camera position. In double, from the float ray.
glm::dvec2 on_plane(const Camera& c, const Ray& ray, double z) {
  const glm::dvec3 o = glm::dvec3(ray.origin) - glm::dvec3(c.position), d(ray.direction);
  const glm::dvec3 f(c.forward);
  const double t = (z - glm::dot(o, f)) / glm::dot(d, f);
  const glm::dvec3 p = o + t * d;
  return {glm::dot(p, glm::dvec3(c.right)), glm::dot(p, glm::dvec3(c.up))};
}

// The film point whose lens ray for `lens_sample` passes through (x, y) on the plane at distance z.
// For a fixed lens point the map film point -> plane point is affine (the focus point is affine in
// the film point, and the ray's origin is fixed), so three rays give it exactly up to rounding.
Vec2 film_point_seeing(const Camera& c, glm::dvec2 target, double z, Vec2 lens_sample, Vec2 guess) {
  auto at = [&](Vec2 f) { return on_plane(c, subject([&] { return generate_lens_ray(c, f, lens_sample); }), z); };
  const glm::dvec2 p0 = at(guess), px = at(guess + Vec2(1, 0)) - p0, py = at(guess + Vec2(0, 1)) - p0;
  const glm::dvec2 r = target - p0;
  const double det = px.x * py.y - px.y * py.x;
  return guess + Vec2(float((r.x * py.y - r.y * py.x) / det), float((px.x * r.y - px.y * r.x) / det));
}

TEST(ThinLens, ApertureZeroGivesThePinholeRaysBitForBit) {
  const Camera pinhole(lens_spec(0.0f, 4.0f), 160, 120);
  Rng rng(3, 0, 0);
  for (int k = 0; k < 2000; ++k) {
    const Vec2 film = Vec2(160.0f, 120.0f) * rng.uniform2();
    const Vec2 lens = rng.uniform2();
    const Ray a = subject([&] { return generate_camera_ray(pinhole, film); });
    const Ray b = subject([&] { return generate_lens_ray(pinhole, film, lens); });
    ASSERT_EQ(a.origin, b.origin);
    ASSERT_EQ(a.direction, b.direction);
  }
}

TEST(ThinLens, RaysStartOnTheLensDiskAndAreUnit) {
  Rng rng(4, 0, 0);
  double farthest = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const Vec2 lens = rng.uniform2();
    const Ray ray = subject([&] { return generate_lens_ray(kLens, Vec2(80.0f, 60.0f), lens); });
    const glm::dvec3 offset = glm::dvec3(ray.origin) - glm::dvec3(kLens.position);
    EXPECT_NEAR(glm::dot(offset, glm::dvec3(kLens.forward)), 0.0, 1e-6) << "the lens lies in the plane facing forward";
    farthest = std::max(farthest, glm::length(offset));
    EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-6f);
  }
  EXPECT_LE(farthest, 0.2 * (1.0 + 1e-6));
  EXPECT_GT(farthest, 0.2 * 0.98) << "lens points reach the aperture's rim";
  // The square's edge maps to the disk's rim: the aperture radius exactly.
  for (const Vec2 u : {Vec2(1.0f, 0.5f), Vec2(0.0f, 0.5f), Vec2(0.5f, 1.0f), Vec2(0.5f, 0.0f), Vec2(1.0f, 1.0f)}) {
    const Ray ray = subject([&] { return generate_lens_ray(kLens, Vec2(10.0f, 100.0f), u); });
    EXPECT_NEAR(glm::length(glm::dvec3(ray.origin) - glm::dvec3(kLens.position)), 0.2, 1e-6) << u.x << ", " << u.y;
  }
}

TEST(ThinLens, APointOnTheFocalPlaneImagesToOneFilmPoint) {
  Rng rng(5, 0, 0);
  for (const Vec2 film : {Vec2(80.0f, 60.0f), Vec2(3.5f, 7.25f), Vec2(150.0f, 110.0f)}) {
    // The pinhole ray through the film point meets the focal plane at the point in focus.
    const glm::dvec2 in_focus = on_plane(kLens, subject([&] { return generate_camera_ray(kLens, film); }), 4.0);
    for (int k = 0; k < 500; ++k) {
      const Vec2 lens = rng.uniform2();
      const glm::dvec2 hit = on_plane(kLens, subject([&] { return generate_lens_ray(kLens, film, lens); }), 4.0);
      ASSERT_NEAR(hit.x, in_focus.x, 2e-5) << "film point " << film.x << ", " << film.y;
      ASSERT_NEAR(hit.y, in_focus.y, 2e-5) << "film point " << film.x << ", " << film.y;
    }
  }
}

// A point at distance z is seen from the film points (its pinhole image) + D (l_x, -l_y) with
// D = (1/s - 1/z) * pixels per film unit, (l_x, l_y) the lens point (film y grows downwards): a disk
// of diameter 2 a |1/s - 1/z| film units, the thin-lens circle of confusion (camera_rays.h).
void expect_circle_of_confusion(double z) {
  const Camera& c = kLens;
  const Vec2 film(100.0f, 40.0f);
  // Its pinhole image is `film`.
  const glm::dvec2 target = on_plane(c, subject([&] { return generate_camera_ray(c, film); }), z);
  const double scale = (1.0 / 4.0 - 1.0 / z) * pixels_per_film_unit(c);
  Rng rng(6, 0, 0);
  double widest = 0.0;
  for (int k = 0; k < 400; ++k) {
    const Vec2 u = k < 8 ? Vec2(k % 2, float(k / 2) / 4.0f) : rng.uniform2();  // the first 8 on the rim
    const Vec2 seen = film_point_seeing(c, target, z, u, film);
    const Vec2 lens = 0.2f * subject([&] { return sample_uniform_disk(u); });
    const glm::dvec2 expected = glm::dvec2(film) + scale * glm::dvec2(lens.x, -lens.y);
    EXPECT_NEAR(seen.x, expected.x, 2e-3) << "z " << z << ", lens sample " << u.x << ", " << u.y;
    EXPECT_NEAR(seen.y, expected.y, 2e-3) << "z " << z << ", lens sample " << u.x << ", " << u.y;
    widest = std::max(widest, glm::length(glm::dvec2(seen) - glm::dvec2(film)));
  }
  // The rim gives the radius itself: a |1/s - 1/z| film units.
  EXPECT_NEAR(widest, 0.2 * std::abs(scale), 2e-3) << "z " << z;
}

TEST(ThinLens, ACloserPointSpreadsOverTheThinLensCircleOfConfusion) { expect_circle_of_confusion(2.0); }
TEST(ThinLens, AFartherPointSpreadsOverTheThinLensCircleOfConfusion) { expect_circle_of_confusion(12.0); }

TEST(ThinLens, FocusDistanceDefaultsToTheLookAtPoint) {
  const CameraSpec spec = lens_spec(0.1f, 0.0f);
  const Camera c(spec, 160, 120);
  EXPECT_FLOAT_EQ(c.focus_distance, glm::length(spec.look_at - spec.position));
  EXPECT_THROW(Camera(lens_spec(-0.1f, 1.0f), 10, 10), std::invalid_argument);
  EXPECT_THROW(Camera(lens_spec(0.1f, -1.0f), 10, 10), std::invalid_argument);
}

// The pixel loop (render.h) takes a lens point only when the camera has an aperture: a pinhole
// draws no lens numbers (so every pinhole render is what it was), a lens draws two after the
// pixel's two, and the ray then starts on the lens. Each pixel's value is recomputed from its own
// sample streams: the radiance returns the next number of the stream after the camera's.
TEST(ThinLens, ThePixelLoopDrawsLensNumbersOnlyWithAnAperture) {
  for (const float aperture : {0.0f, 0.3f}) {
    const Camera camera(lens_spec(aperture, 4.0f), 6, 4);
    RenderSettings settings;
    settings.width = 6, settings.height = 4, settings.spp = 5, settings.seed = 9;
    const auto [image, rays_on_lens] = subject([&] {
      int on_lens = 0;
      Image rendered = render_image(camera, settings, 1, [&](const Ray& ray, Rng& rng) {
        on_lens += glm::length(ray.origin - camera.position) > 0.0f ? 1 : 0;
        return Color(rng.uniform());
      });
      return std::pair(std::move(rendered), on_lens);
    });
    EXPECT_EQ(rays_on_lens, aperture > 0.0f ? 6 * 4 * 5 : 0)
        << "a lens ray starts on the lens, a pinhole ray at the pinhole";
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 6; ++x) {
        Color sum(0.0f);
        for (int k = 0; k < 5; ++k) {
          Rng rng(9, std::uint64_t(y * 6 + x), std::uint64_t(k));
          rng.uniform2();                       // the pixel's offset
          if (aperture > 0.0f) rng.uniform2();  // the lens point
          sum += Color(rng.uniform());
        }
        EXPECT_EQ(image.at(x, y), sum / 5.0f) << "aperture " << aperture << ", pixel " << x << ", " << y;
      }
  }
}

// The concentric map: uniform on the disk (chi-square on rings of equal area and sectors), and one
// to one (its inverse gives back u).
TEST(DiskSampling, ConcentricMapIsUniformOverTheDisk) {
  constexpr int kRings = 20, kSectors = 40, kSamples = 1000000;
  std::vector<double> observed(kRings * kSectors + 1, 0.0), expected(kRings * kSectors + 1, 0.0);
  const std::vector<Vec2> points = subject([&] {
    std::vector<Vec2> drawn(kSamples);
    Rng rng(7, 0, 0);
    for (Vec2& p : drawn) p = sample_uniform_disk(rng.uniform2());
    return drawn;
  });
  for (const Vec2 p : points) {
    const double s = double(p.x) * p.x + double(p.y) * p.y;  // r^2: rings of equal r^2 have equal area
    double phi = std::atan2(double(p.y), double(p.x));
    if (phi < 0.0) phi += 2.0 * testing::kPiD;
    if (s > 1.0 + 1e-6) {
      observed.back() += 1.0;  // outside the disk, where the pdf is 0
      continue;
    }
    const int i = std::min(kRings - 1, int(s * kRings));
    const int j = std::min(kSectors - 1, int(phi / (2.0 * testing::kPiD) * kSectors));
    observed[size_t(i * kSectors + j)] += 1.0;
  }
  // uniform_disk_pdf = 1/pi per unit area; a bin of r^2 in [i, i+1)/R and phi in a 1/S turn has
  // area pi / (R S), so it expects N / (R S). The centre of each bin checks the pdf's value.
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSectors; ++j) {
      const double r = std::sqrt((i + 0.5) / kRings), phi = 2.0 * testing::kPiD * (j + 0.5) / kSectors;
      const double area = testing::kPiD / (kRings * kSectors);
      expected[size_t(i * kSectors + j)] =
          kSamples * area * uniform_disk_pdf(Vec2(float(r * std::cos(phi)), float(r * std::sin(phi))));
    }
  const auto r = testing::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(DiskSampling, InvertingASampleGivesBackItsNumbers) {
  for (int i = 1; i < 40; ++i)
    for (int j = 1; j < 40; ++j) {
      const Vec2 u(float(i) / 40.0f, float(j) / 40.0f);
      const Vec2 back = invert_uniform_disk(subject([&] { return sample_uniform_disk(u); }));
      EXPECT_NEAR(back.x, u.x, 2e-5f) << u.x << ", " << u.y;
      EXPECT_NEAR(back.y, u.y, 2e-5f) << u.x << ", " << u.y;
    }
}

}  // namespace
}  // namespace rt
