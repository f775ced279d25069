// The caustic scene (assets/scenes/caustic.json), where path tracing fails: at the same number of
// samples, BDPT and SPPM find the caustic with a small fraction of path tracing's error (the time
// each takes is benchmarks/transport_error_vs_time.cpp's to measure), and light tracing cannot see
// glass at all.
#include "common/image_io.h"

#include "stage6/loaded_scene.h"
#include "stage6/scene_regions.h"
#include "stage6/transport_estimates.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

// The caustic scene on its reference's 128 x 96 film, and the reference.
const testing::LoadedScene& caustic_scene() {
  static const testing::LoadedScene s("assets/scenes/caustic.json", 128, 96);
  return s;
}
const Image& caustic_reference() {
  static const Image reference = read_pfm(testing::source_path("assets/references/caustic-128x96.pfm"));
  return reference;
}


TEST(CausticScene, BdptAndSppmFindTheCausticWherePathTracingCannot) {
  const testing::LoadedScene& c = caustic_scene();
  const Image& reference = caustic_reference();
  TransportOptions sppm = method(TransportMethod::sppm);
  sppm.sppm.photons_per_pass = 20000;
  const double pt = rmse(render_method(c.scene, c.camera, method(TransportMethod::pt), 32, 3), reference,
                                kCausticRegion);
  const Image bdpt_image = render_method(c.scene, c.camera, method(TransportMethod::bdpt), 32, 3);
  const Image sppm_image = render_method(c.scene, c.camera, sppm, 32, 3);
  const double bdpt = rmse(bdpt_image, reference, kCausticRegion);
  const double photons = rmse(sppm_image, reference, kCausticRegion);
  // Measured: path tracing 4.4, BDPT 0.12, SPPM 0.17 (the caustic's mean radiance is 1.6).
  EXPECT_GT(pt, 10.0 * bdpt);
  EXPECT_GT(pt, 10.0 * photons);
  const double expected = grey(mean_over(reference, kCausticRegion));
  EXPECT_NEAR(grey(mean_over(bdpt_image, kCausticRegion)), expected, 0.05 * expected);
  EXPECT_NEAR(grey(mean_over(sppm_image, kCausticRegion)), expected, 0.05 * expected);
}

TEST(CausticScene, LightTracingCannotSeeGlass) {
  // A pinhole is reached from a delta lobe only if the lobe points exactly at it: inside the ball's
  // silhouette light tracing adds nothing, where the reference shows the room refracted.
  const testing::LoadedScene& c = caustic_scene();
  const Image& reference = caustic_reference();
  const Image lt = render_method(c.scene, c.camera, method(TransportMethod::lt), 16, 3);
  EXPECT_EQ(mean_over(lt, kBallRegion), DVec3(0.0));
  EXPECT_GT(grey(mean_over(reference, kBallRegion)), 0.05);
  // ... while it does find the caustic on the floor.
  EXPECT_GT(grey(mean_over(lt, kCausticRegion)), 0.8 * grey(mean_over(reference, kCausticRegion)));
}

}  // namespace
}  // namespace rt
