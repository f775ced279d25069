// Stage 6's photon mapping: the progressive radius reduction by hand, the photon grid against a
// search of every photon, the white furnace in the limit, and the error falling with the passes.
#include "06-light-transport/photon_grid.h"
#include "common/image_io.h"

#include "stage5/path_estimates.h"
#include "stage6/records.h"
#include "stage6/transport_estimates.h"
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace rt {
namespace {

// progressive_update taken through subject(): the statistics after one pass's photons.
PhotonStatistics updated(PhotonStatistics s, int photons, Color flux, float alpha) {
  return testing::subject([&] {
    progressive_update(s, photons, flux, alpha);
    return s;
  });
}

TEST(ProgressiveUpdate, ByHand) {
  // Hachisuka & Jensen's reduction with N = 0, M = 9, alpha = 2/3: N' = 6, r'^2 = r^2 6 / 9,
  // tau' = (tau + Phi) 6 / 9.
  PhotonStatistics s{0.0, 3.0f, Color(1.0f)};
  s = updated(s, 9, Color(2.0f, 5.0f, 8.0f), 2.0f / 3.0f);
  EXPECT_NEAR(s.photons, 6.0, 1e-6);
  EXPECT_NEAR(s.radius, 3.0f * std::sqrt(6.0f / 9.0f), 1e-6f);
  EXPECT_NEAR(s.tau.x, 3.0f * 6.0f / 9.0f, 1e-6f);
  EXPECT_NEAR(s.tau.z, 9.0f * 6.0f / 9.0f, 1e-5f);
  // A second pass: N = 6, M = 3: N' = 8, r'^2 = r^2 8 / 9.
  const float r = s.radius;
  const Color tau = s.tau;
  s = updated(s, 3, Color(1.0f), 2.0f / 3.0f);
  EXPECT_NEAR(s.photons, 8.0, 1e-6);
  EXPECT_NEAR(s.radius, r * std::sqrt(8.0f / 9.0f), 1e-6f);
  EXPECT_NEAR(s.tau.y, (tau.y + 1.0f) * 8.0f / 9.0f, 1e-5f);
}

TEST(ProgressiveUpdate, NoPhotonsNoChangeAndAlphaOneKeepsTheRadius) {
  PhotonStatistics s{4.0, 2.0f, Color(3.0f)};
  s = updated(s, 0, Color(0.0f), 2.0f / 3.0f);
  EXPECT_EQ(s.photons, 4.0);
  EXPECT_EQ(s.radius, 2.0f);
  EXPECT_EQ(s.tau, Color(3.0f));
  s = updated(s, 5, Color(1.0f), 1.0f);  // keep every photon: plain photon mapping
  EXPECT_EQ(s.radius, 2.0f);
  EXPECT_NEAR(s.tau.x, 4.0f, 1e-6f);
  EXPECT_NEAR(s.photons, 9.0, 1e-9);
}

TEST(PhotonRadiance, FluxOverDiskAreaAndPhotonCount) {
  const PhotonStatistics s{10.0, 0.5f, Color(kPi)};
  EXPECT_NEAR(RT_GRADED(photon_radiance)(s, 100.0).x, kPi / (kPi * 0.25f * 100.0f), 1e-6f);
  EXPECT_EQ(RT_GRADED(photon_radiance)(s, 0.0), Color(0.0f));
}

TEST(PhotonGrid, FindsExactlyThePhotonsWithinTheRadius) {
  Rng rng(4, 0, 0);
  std::vector<Photon> photons;
  for (int i = 0; i < 5000; ++i) {
    // Clustered on a lattice, so many photons sit exactly on cell faces and at the radius.
    const Vec3 p = i % 3 == 0 ? glm::floor(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 8.0f) * 0.25f
                              : Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - Vec3(0.5f);
    photons.push_back(Photon{p, Vec3(0, 0, 1), Color(float(i))});
  }
  const float radius = 0.25f;
  const PhotonGrid grid(photons, 2.0f * radius);
  EXPECT_EQ(grid.size(), photons.size());
  for (int q = 0; q < 300; ++q) {
    const Vec3 x = q % 2 ? glm::floor(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 8.0f) * 0.25f
                         : Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - Vec3(0.5f);
    const float r = radius * (q % 3 ? 1.0f : rng.uniform());
    std::vector<float> found, expected;
    grid.for_each_within(x, r, [&](const Photon& p) { found.push_back(p.power.x); });
    for (const Photon& p : photons)
      if (glm::dot(p.position - x, p.position - x) <= r * r) expected.push_back(p.power.x);
    std::vector<float> sorted = found;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, expected) << "query " << q;  // each once, none missed (expected is in index order)
  }
  // The same query twice visits the photons in the same order.
  std::vector<float> first, second;
  grid.for_each_within(Vec3(0.5f), radius, [&](const Photon& p) { first.push_back(p.power.x); });
  grid.for_each_within(Vec3(0.5f), radius, [&](const Photon& p) { second.push_back(p.power.x); });
  EXPECT_EQ(first, second);
  EXPECT_FALSE(first.empty());
}

TEST(PhotonGrid, FarPointsAndEmptyGrids) {
  const PhotonGrid empty(std::vector<Photon>{}, 1.0f);
  int visits = 0;
  empty.for_each_within(Vec3(0.0f), 1.0f, [&](const Photon&) { ++visits; });
  EXPECT_EQ(visits, 0);
  // Coordinates far beyond int range per cell: clamped into the border cells, still found by distance.
  const PhotonGrid far({Photon{Vec3(1e12f, -1e12f, 0.0f), Vec3(0, 0, 1), Color(1.0f)}}, 1e-3f);
  far.for_each_within(Vec3(1e12f, -1e12f, 0.0f), 1.0f, [&](const Photon&) { ++visits; });
  EXPECT_EQ(visits, 1);
  EXPECT_THROW(PhotonGrid(std::vector<Photon>{}, 0.0f), std::invalid_argument);
}

TEST(PhotonGrid, AssignedAgainItHoldsOnlyTheNewPhotons) {
  // A renderer keeps one grid and assigns each pass's photons to it: nothing of a larger pass, its
  // photons or its buckets, may show through a smaller one built with another cell size.
  std::vector<Photon> many;
  for (int i = 0; i < 1000; ++i)
    many.push_back(Photon{Vec3(float(i % 10), float(i / 10 % 10), 0.0f) * 0.1f, Vec3(0, 0, 1), Color(float(i))});
  PhotonGrid grid;
  int visits = 0;
  grid.for_each_within(Vec3(0.0f), 10.0f, [&](const Photon&) { ++visits; });
  EXPECT_EQ(visits, 0);  // a grid made empty finds nothing
  grid.assign(std::span(&many, 1), 0.2f);
  grid.for_each_within(Vec3(0.0f), 10.0f, [&](const Photon&) { ++visits; });
  EXPECT_EQ(visits, 1000);
  const std::vector<Photon> few = {Photon{Vec3(0.05f, 0.0f, 0.0f), Vec3(0, 0, 1), Color(-1.0f)},
                                   Photon{Vec3(0.0f, 0.3f, 0.0f), Vec3(0, 0, 1), Color(-2.0f)}};
  grid.assign(std::span(&few, 1), 0.7f);
  EXPECT_EQ(grid.size(), 2u);
  std::vector<float> found;
  grid.for_each_within(Vec3(0.0f), 0.35f, [&](const Photon& p) { found.push_back(p.power.x); });
  EXPECT_EQ(found, (std::vector<float>{-1.0f, -2.0f}));  // both new photons, in their order, no old one
  EXPECT_THROW(grid.assign(std::span(&few, 1), 0.0f), std::invalid_argument);
}

TEST(SppmFurnace, FindsTheClosedFormRadiance) {
  // Inside a closed cube of albedo 1/2 whose walls all emit Le = 1: L = Le / (1 - albedo) = 2
  // everywhere. The visible point sees Le, samples the direct light, and the photons bring the rest.
  const LightingScene scene = furnace(0.5f, 1.0f);
  CameraSpec spec;  // at the centre, looking at the middle of a wall, far from its edges
  spec.vfov_degrees = 20.0f;
  const Camera camera(spec, 8, 8);
  TransportOptions options = method(TransportMethod::sppm);
  options.sppm.photons_per_pass = 4000;
  const PixelRect all[] = {{0, 0, 8, 8}};
  const std::vector<RegionEstimate> e = region_estimates(
      [&](std::uint64_t seed) { return render_method(scene, camera, options, 32, seed); }, all, 8);
  EXPECT_NEAR(e[0].mean, 2.0, 3.0 * e[0].standard_error);
  EXPECT_LT(e[0].standard_error, 0.03);  // a real error bar, not one any answer passes
}

TEST(SppmConvergence, ErrorFallsWithThePasses) {
  // RMSE against the converged Cornell box (stage 5's reference) after 4, 16 and 64 passes: both
  // the noise and the bias shrink, so the error falls; its log-log slope is measured.
  const SceneDescription description = load_scene(testing::source_path("assets/scenes/cornell-box.json"));
  const LightingScene scene(description);
  const Camera camera(description.camera, 32, 32);
  const Image reference = downsample(read_pfm(testing::source_path("assets/references/cornell-box-256.pfm")), 8);
  TransportOptions options = method(TransportMethod::sppm);
  options.sppm.photons_per_pass = 10000;
  std::vector<double> errors;
  for (const int passes : {4, 16, 64}) errors.push_back(rmse(render_method(scene, camera, options, passes, 1), reference));
  const double slope = std::log(errors[2] / errors[0]) / std::log(16.0);
  std::printf("SPPM RMSE after 4, 16, 64 passes: %.4f %.4f %.4f, slope %.2f\n", errors[0], errors[1], errors[2], slope);
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
  EXPECT_LT(slope, -0.3);
}

}  // namespace
}  // namespace rt
