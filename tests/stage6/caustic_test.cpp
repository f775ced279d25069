// The caustic scene (assets/scenes/caustic.json), where path tracing fails: at the same number of
// samples, BDPT and SPPM find the caustic with a small fraction of path tracing's error (the time
// each takes is benchmarks/transport_error_vs_time.cpp's to measure), and light tracing cannot see
// glass at all.
#include "common/image_io.h"
#include "common/scene.h"

#include "stage6/loaded_scene.h"
#include "stage6/scene_regions.h"
#include "stage6/transport_estimates.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

// A sheet of glass (index 1.5) over the caustic scene's floor, lit from straight above, whose
// vertex normals lean 30 degrees from the geometric one: the light below it arrives through one
// refraction, where radiance and importance differ by (eta_t / eta_i)^2, at a shading normal, where
// their cosines enter the other way round (stage 4's TransportMode, ShadingPoint::sample).
testing::LoadedScene glass_sheet_scene(const std::filesystem::path& folder) {
  const float lean = 30.0f * kPi / 180.0f;
  std::string obj;
  for (const char* corner : {"-1.5 1.5 -1.5", "-1.5 1.5 1.5", "1.5 1.5 1.5", "1.5 1.5 -1.5"})
    obj += std::string("v ") + corner + "\n";
  for (int i = 0; i < 4; ++i)
    obj += "vn " + std::to_string(std::sin(lean)) + " " + std::to_string(std::cos(lean)) + " 0\n";
  obj += "f 1//1 2//2 3//3\nf 1//1 3//3 4//4\n";
  testing::write_text(folder / "sheet.obj", obj);
  std::string text = testing::read_text(testing::source_path("assets/scenes/caustic.json"));
  const auto replace = [&](const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
  };
  replace(R"({ "type": "sphere", "name": "glass ball", "center": [0, 1, 0], "radius": 1, "material": "glass" })",
          R"({ "type": "mesh", "name": "glass sheet", "file": "sheet.obj", "material": "glass" })");
  replace("[[-1.1, 4.2, 0.8], [-1.1, 4.2, 1.0], [-1.3, 4.2, 1.0], [-1.3, 4.2, 0.8]]",
          "[[0.5, 4.2, -0.5], [0.5, 4.2, 0.5], [-0.5, 4.2, 0.5], [-0.5, 4.2, -0.5]]");
  replace("[500, 475, 425]", "[50, 48, 45]");
  return testing::LoadedScene(parse_scene(text, (folder / "glass-sheet.json").string()), 128, 96);
}

TEST(CausticScene, LightAndPathTracingAgreeUnderGlassWithShadingNormals) {
  testing::ScratchDir folder;
  const testing::LoadedScene c = glass_sheet_scene(folder.path());
  // The floor under the sheet, and beside it where the refracted light spreads.
  constexpr PixelRect kRegions[] = {{20, 60, 110, 96}, {0, 50, 20, 96}};
  const auto estimates = [&](TransportMethod m) {
    return region_estimates([&](std::uint64_t seed) { return render_method(c.scene, c.camera, method(m), 64, seed); },
                            kRegions, 8);
  };
  const std::vector<RegionEstimate> pt = estimates(TransportMethod::pt), lt = estimates(TransportMethod::lt);
  // Measured: under the sheet 0.502 +- 0.003 (pt) and 0.503 +- 0.001 (lt); with the light tracer's
  // refraction weighed as radiance's, lt gives 0.23 (87 standard errors off); without the shading
  // normals' correction, 0.57 (22 off).
  for (size_t r = 0; r < std::size(kRegions); ++r) {
    const double error = std::hypot(pt[r].standard_error, lt[r].standard_error);
    EXPECT_NEAR(lt[r].mean, pt[r].mean, 4.0 * error) << "region " << r;
    EXPECT_GT(pt[r].mean, 0.05) << "region " << r << " is lit";
    EXPECT_LT(error, 0.02 * pt[r].mean) << "region " << r << ": the error bar is tight enough to tell";
  }
}

}  // namespace
}  // namespace rt
