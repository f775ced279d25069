// Hidden tests of stage 7: the VCM weight on a four-vertex path by hand, at densities no visible
// test uses, a merge on a glossy wall, where the BSDF depends on both directions, and MLT's
// acceptance and small step at random inputs.
#include "01-ray-casting/camera_rays.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "07-vcm-mlt/mlt.h"
#include "07-vcm-mlt/vcm.h"
#include "stage6/loaded_scene.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <array>

namespace rt {
namespace {

TEST(HiddenVcmWeight, ByHandOnAFourVertexPath) {
  // x_0 ... x_3: connections t = 1 ... 4 and merges at x_1, x_2.
  const float pc[] = {1.0f, 0.3f, 2.5f, 0.9f}, pl[] = {1.0f, 1.7f, 0.4f, 6.0f}, eta = 2.2f;
  std::vector<PathDensity> path;
  for (int i = 0; i < 4; ++i) path.push_back({pc[i], pl[i], false});
  const auto connection = [&](int t) {
    double p = 1.0;
    for (int j = 0; j < 4; ++j) p *= j < t ? pc[j] : pl[j];
    return p;
  };
  const double p[] = {connection(1),
                      connection(2),
                      connection(3),
                      connection(4),
                      eta * pl[1] * connection(2),
                      eta * pl[2] * connection(3)};
  double sum = 0.0;
  for (const double d : p) sum += d * d;
  const Technique techniques[] = {{Technique::connection, 1}, {Technique::connection, 2}, {Technique::connection, 3},
                                  {Technique::connection, 4}, {Technique::merge, 2},      {Technique::merge, 3}};
  const std::vector<float> w = testing::subject([&] {
    std::vector<float> out;
    for (const Technique m : techniques) out.push_back(vcm_weight(path, m, VcmTechniques{.eta = eta}));
    return out;
  });
  ASSERT_EQ(w.size(), 6u);
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(w[i], p[i] * p[i] / sum, 1e-6) << i;
}

TEST(HiddenVcmMerge, OnAGlossyWallTheBsdfSeesBothDirections) {
  const testing::LoadedScene& s = testing::glossy_cornell_box<64, 48>();
  std::vector<PathVertex> camera_path{camera_vertex(s.camera)}, light_path;
  const Ray ray = generate_camera_ray(s.camera, Vec2(40.0f, 18.0f));
  WalkSettings walk;
  walk.max_vertices = 2;
  Rng rng(9, 0, 0);
  // (merged, f at z for the direction the light arrived from, f for the direction from z towards y)
  const auto [merged, f, f_wrong] = testing::subject([&] {
    random_walk(s.scene, ray, Color(1.0f), camera_direction_pdf(s.camera, ray.direction), walk, rng, camera_path);
    light_path.push_back(*sample_light_vertex(s.scene, 0.3f, Vec2(0.2f, 0.7f)));
    PathVertex y = camera_path.at(1);
    y.hit.point += Vec3(5.0f, 0.0f, 0.0f);  // beside z on the wall: within a merge radius of it
    y.beta = Color(0.5f);
    light_path.push_back(y);
    const PathVertex& z = camera_path[1];
    const Vec3 wo = z.direction_to(camera_path[0]);
    return std::tuple(merge_contribution(camera_path, light_path, 2, 2, 3.0f),
                      scattering(z, wo, y.direction_to(light_path[0])), scattering(z, wo, z.direction_to(y)));
  });
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(merged[c], f[c] * 0.5f / 3.0f, 1e-5f * f[c]) << c;
  EXPECT_GT(std::abs(f.x - f_wrong.x), 0.1f * f.x);  // a merge that took z -> y for the light's direction
}

TEST(HiddenMlt, AcceptanceAndSmallStepAtRandomInputs) {
  Rng rng(7070, 0, 0);
  std::vector<std::array<float, 7>> cases;  // current, proposed, x, n, sigma, u1, u2
  for (int i = 0; i < 200; ++i) {
    std::array<float, 7> c;
    for (float& v : c) v = rng.uniform();
    c[0] = i % 10 == 0 ? 0.0f : 5.0f * c[0];
    c[1] *= 5.0f;
    c[3] = float(int(c[3] * 6.0f));
    c[4] *= 0.1f;
    cases.push_back(c);
  }
  const std::vector<std::pair<float, float>> got = testing::subject([&] {
    std::vector<std::pair<float, float>> out;
    for (const auto& c : cases)
      out.emplace_back(acceptance(c[0], c[1]), small_step(c[2], std::int64_t(c[3]), c[4], Vec2(c[5], c[6])));
    return out;
  });
  ASSERT_EQ(got.size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    EXPECT_NEAR(got[i].first, c[0] > 0.0f ? std::min(1.0f, c[1] / c[0]) : 1.0f, 1e-6f) << i;
    const double z = std::sqrt(-2.0 * std::log(1.0 - c[5])) * std::cos(2.0 * 3.14159265358979 * c[6]);
    double x = c[2] + z * c[4] * std::sqrt(double(c[3]));
    x -= std::floor(x);
    const double d = std::abs(got[i].second - x);
    EXPECT_LT(std::min(d, 1.0 - d), 1e-5) << i;  // the same point of the circle [0, 1)
  }
}

}  // namespace
}  // namespace rt
