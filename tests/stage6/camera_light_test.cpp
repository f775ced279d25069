// Stage 6's two ends of a path: the pinhole as a sensor (its film projection and importance) and
// the emitters as sources (where light leaves, in which direction, with which densities).
#include "01-ray-casting/camera_rays.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "stage6/records.h"
#include "common/random.h"

#include "support/chi_square.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

Camera test_camera(int width = 200, int height = 100) {
  CameraSpec spec;
  spec.position = Vec3(1.0f, 2.0f, 3.0f);
  spec.look_at = Vec3(2.0f, 1.5f, 6.0f);
  spec.vfov_degrees = 50.0f;
  return Camera(spec, width, height);
}

TEST(ProjectToFilm, InvertsTheCameraRay) {
  const Camera camera = test_camera();
  Rng rng(3, 0, 0);
  for (int k = 0; k < 1000; ++k) {
    const Vec2 film(rng.uniform() * 200.0f, rng.uniform() * 100.0f);
    const Ray ray = RT_GRADED(generate_camera_ray)(camera, film);
    const std::optional<Vec2> back = RT_GRADED(project_to_film)(camera, ray.at(0.5f + 20.0f * rng.uniform()));
    ASSERT_TRUE(back) << film.x << ", " << film.y;
    EXPECT_NEAR(back->x, film.x, 2e-3f);
    EXPECT_NEAR(back->y, film.y, 2e-3f);
  }
}

TEST(ProjectToFilm, NothingBehindTheCameraOrOffTheFilm) {
  const Camera camera = test_camera();
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, camera.position - camera.forward));
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, camera.position));  // at the pinhole itself
  // Just outside each edge of the film, and just inside.
  const auto at = [&](float x, float y) { return RT_GRADED(generate_camera_ray)(camera, Vec2(x, y)).at(5.0f); };
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, at(-0.01f, 50.0f)));
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, at(200.01f, 50.0f)));
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, at(100.0f, -0.01f)));
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, at(100.0f, 100.01f)));
  EXPECT_TRUE(RT_GRADED(project_to_film)(camera, at(0.01f, 0.01f)));
  EXPECT_TRUE(RT_GRADED(project_to_film)(camera, at(199.99f, 99.99f)));
}

TEST(ProjectToFilm, TheFilmsFarEdgeBelongsToNoPixel) {
  // A point whose film x is exactly the width would be pixel `width`, one past the last: the film
  // is [0, width) x [0, height), as the pixel loop's samples are. Built on the axes, where the
  // projection is exact: a camera at the origin looking down +z with a 90 degree field.
  CameraSpec spec;
  spec.vfov_degrees = 90.0f;
  const Camera camera(spec, 2, 2);
  ASSERT_NEAR(camera.tan_half_vfov, 1.0f, 1e-6f);
  EXPECT_TRUE(RT_GRADED(project_to_film)(camera, Vec3(0.0f, 0.0f, 1.0f)));
  const std::optional<Vec2> corner =
      RT_GRADED(project_to_film)(camera, Vec3(0.999f, 0.999f, 1.0f));  // +x is on the left
  ASSERT_TRUE(corner);
  EXPECT_LT(corner->x, 0.01f);
  EXPECT_LT(corner->y, 0.01f);
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, Vec3(-1.0f, 0.0f, 1.0f)));  // film x = 2 = width: off the film
  EXPECT_FALSE(RT_GRADED(project_to_film)(camera, Vec3(0.0f, -1.0f, 1.0f)));  // film y = 2 = height
}

// The other edge is the film's: film x or y exactly 0 is pixel 0 ("x > 0" survived every test
// above). The points are built from the camera's own factors, so the projection gives exactly 0.
TEST(ProjectToFilm, TheFilmsNearEdgeBelongsToTheFirstPixel) {
  CameraSpec spec;
  spec.vfov_degrees = 90.0f;
  const Camera camera(spec, 3, 2);
  ASSERT_EQ(camera.right, Vec3(-1.0f, 0.0f, 0.0f));  // looking down +z, +x on the left
  ASSERT_EQ(camera.up, Vec3(0.0f, 1.0f, 0.0f));
  const std::optional<Vec2> left =
      RT_GRADED(project_to_film)(camera, Vec3(camera.aspect * camera.tan_half_vfov, 0.0f, 1.0f));
  ASSERT_TRUE(left) << "film x = 0 is on the film";
  EXPECT_EQ(left->x, 0.0f);
  const std::optional<Vec2> top = RT_GRADED(project_to_film)(camera, Vec3(0.0f, camera.tan_half_vfov, 1.0f));
  ASSERT_TRUE(top) << "film y = 0 is on the film";
  EXPECT_EQ(top->y, 0.0f);
}

// The importance integrates to 1 over the film's directions, weighted by the projected solid
// angle: a uniform radiance 1 makes an image of 1 (We normalizes the whole film).
TEST(CameraImportance, IntegratesToOneOverTheFilm) {
  const Camera camera = test_camera();
  Rng rng(5, 0, 0);
  double importance = 0.0, density = 0.0;
  const int n = 400000;
  for (int k = 0; k < n; ++k) {
    const float z = 1.0f - 2.0f * rng.uniform(), phi = 2.0f * kPi * rng.uniform();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const Vec3 w(r * std::cos(phi), r * std::sin(phi), z);
    const float cos_theta = glm::dot(w, camera.forward);
    importance += RT_GRADED(camera_importance)(camera, w) * std::max(0.0f, cos_theta) * 4.0 * kPi;
    density += RT_GRADED(camera_direction_pdf)(camera, w) * 4.0 * kPi;
  }
  EXPECT_NEAR(importance / n, 1.0, 0.02);
  EXPECT_NEAR(density / n, 1.0, 0.02);
}

TEST(CameraImportance, ClosedFormOnTheAxisAndOffIt) {
  const Camera camera = test_camera();
  const float area = RT_GRADED(film_area)(camera);
  EXPECT_NEAR(area, 4.0f * camera.tan_half_vfov * camera.tan_half_vfov * 2.0f, 1e-5f);
  EXPECT_NEAR(RT_GRADED(camera_importance)(camera, camera.forward), 1.0f / area, 1e-6f);
  const Ray corner = RT_GRADED(generate_camera_ray)(camera, Vec2(150.0f, 20.0f));
  const float c = glm::dot(corner.direction, camera.forward);
  EXPECT_NEAR(RT_GRADED(camera_importance)(camera, corner.direction), 1.0f / (area * c * c * c * c), 1e-5f);
  EXPECT_NEAR(RT_GRADED(camera_direction_pdf)(camera, corner.direction), 1.0f / (area * c * c * c), 1e-5f);
  EXPECT_EQ(RT_GRADED(camera_importance)(camera, -camera.forward), 0.0f);
  EXPECT_EQ(RT_GRADED(camera_importance)(camera, glm::normalize(camera.forward + 5.0f * camera.up)),
            0.0f);  // above the film
}

// Two quad lights of different power and a disk: which emitter, where on it, which direction.
LightingScene emitters_scene() {
  return LightingScene(parse_scene(R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"dim": {"albedo": [0, 0, 0], "emission": [1, 1, 1]},
                  "bright": {"albedo": [0, 0, 0], "emission": [3, 3, 3]}},
    "shapes": [{"type": "quad", "material": "dim", "vertices": [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]]},
               {"type": "quad", "material": "bright", "vertices": [[5, 0, 0], [5, 0, 1], [5, 1, 1], [5, 1, 0]]},
               {"type": "disk", "material": "dim", "center": [0, 3, 0], "normal": [0, -1, 0], "radius": 0.5}]})",
                                   "emitters.json"));
}

TEST(EmissionSampling, EmittersByPowerPointsUniformDirectionsByCosine) {
  const LightingScene scene = emitters_scene();
  ASSERT_EQ(scene.emitters().size(), 3u);
  // Powers pi Le A: 2 pi, 3 pi, pi / 4 pi... the choice follows them.
  double total_power = 0.0;
  for (const AreaEmitter& e : scene.emitters()) total_power += double(e.power());
  std::vector<double> chosen(3, 0.0), expected_choice(3, 0.0), cos_bins(10, 0.0), cos_expected(10, 0.0),
      x_bins(8, 0.0), x_expected(8, 0.0);
  const int n = 200000;
  Rng rng(11, 0, 0);
  for (int k = 0; k < n; ++k) {
    const std::optional<EmissionSample> s =
        RT_GRADED(sample_emission)(scene, rng.uniform(), rng.uniform2(), rng.uniform2());
    ASSERT_TRUE(s);
    const int i = s->origin.emitter;
    chosen[size_t(i)] += 1.0;
    const AreaEmitter& e = scene.emitters()[size_t(i)];
    EXPECT_NEAR(s->pdf_position, scene.emitter_distribution().pmf(i) / e.area(), 1e-6f);
    const float cos_theta = glm::dot(s->direction, s->origin.hit.normal);
    ASSERT_GT(cos_theta, 0.0f);
    EXPECT_NEAR(s->pdf_direction, cos_theta / kPi, 1e-5f);
    EXPECT_NEAR(glm::dot(s->origin.hit.normal, e.normal_at(s->origin.hit.point)), 1.0f, 1e-5f);  // the front
    cos_bins[std::min(size_t(9), size_t(cos_theta * 10.0f))] += 1.0;
    if (i == 0) {
      // On the first quad, [0, 2] x [0, 1] at z = 0: uniform in x.
      EXPECT_NEAR(s->origin.hit.point.z, 0.0f, 1e-6f);
      x_bins[std::min(size_t(7), size_t(s->origin.hit.point.x * 4.0f))] += 1.0;
    }
  }
  for (size_t i = 0; i < 3; ++i) expected_choice[i] = n * double(scene.emitters()[i].power()) / total_power;
  // A cosine lobe puts a share cos^2(a) - cos^2(b) of its directions between cos(theta) = a and b.
  for (int b = 0; b < 10; ++b) cos_expected[size_t(b)] = n * (std::pow((b + 1) / 10.0, 2) - std::pow(b / 10.0, 2));
  for (double& x : x_expected) x = chosen[0] / 8.0;
  const testing::ChiSquareResult choice = testing::chi_square_test(chosen, expected_choice);
  const testing::ChiSquareResult lobe = testing::chi_square_test(cos_bins, cos_expected);
  const testing::ChiSquareResult area = testing::chi_square_test(x_bins, x_expected);
  EXPECT_TRUE(choice.passed) << choice.message;
  EXPECT_TRUE(lobe.passed) << lobe.message;
  EXPECT_TRUE(area.passed) << area.message;
}

TEST(EmissionSampling, EachSampleCarriesTheFluxOverTheChoice) {
  // beta = Le cos / (P p_A p_w) = pi A Le / P: the mean over samples is the scene's whole flux.
  const LightingScene scene = emitters_scene();
  double flux = 0.0, mean = 0.0;
  for (const AreaEmitter& e : scene.emitters()) flux += kPi * double(e.area()) * double(e.radiance.x);
  const int n = 20000;
  Rng rng(12, 0, 0);
  for (int k = 0; k < n; ++k) {
    const std::optional<EmissionSample> s =
        RT_GRADED(sample_emission)(scene, rng.uniform(), rng.uniform2(), rng.uniform2());
    ASSERT_TRUE(s);
    const float cos_theta = glm::dot(s->direction, s->origin.hit.normal);
    const double beta = double(s->radiance.x) * cos_theta / (double(s->pdf_position) * s->pdf_direction);
    const AreaEmitter& e = scene.emitters()[size_t(s->origin.emitter)];
    EXPECT_NEAR(beta, kPi * e.area() * e.radiance.x / scene.emitter_distribution().pmf(s->origin.emitter),
                1e-3 * beta);
    mean += beta / n;
  }
  EXPECT_NEAR(mean, flux, 0.02 * flux);
}

TEST(EmissionSampling, NothingWithoutAnEmitter) {
  const LightingScene scene(parse_scene(R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
    "shapes": [{"type": "sphere", "material": "grey", "center": [0, 0, 0], "radius": 1}]})",
                                        "dark.json"));
  EXPECT_FALSE(RT_GRADED(sample_emission)(scene, 0.5f, Vec2(0.5f), Vec2(0.5f)));
}

}  // namespace
}  // namespace rt
