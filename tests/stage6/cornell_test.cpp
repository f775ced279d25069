// Stage 6 on the Cornell box, where every method must agree: light tracing, BDPT and SPPM against
// stage 5's converged reference (assets/references/cornell-box-256.pfm, averaged down to 64 x 64),
// region by region, and the image the same bit for bit for any thread count.
#include "common/image_io.h"

#include "stage6/loaded_scene.h"
#include "stage6/transport_estimates.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

// The 256 x 256 reference averaged down to the tests' 64 x 64 film.
const Image& cornell_reference() {
  static const Image reference = downsample(read_pfm(testing::source_path("assets/references/cornell-box-256.pfm")), 4);
  return reference;
}

// The regions of stage 5's Cornell test, each inside one surface.
const PixelRect kRegions[] = {{36, 14, 46, 24}, {20, 57, 30, 61}, {4, 16, 11, 40}, {53, 16, 60, 40}, {14, 2, 50, 6}};
const char* const kRegionNames[] = {"back wall", "floor between the blocks", "red wall", "green wall", "ceiling"};

// Every region's mean within 3 standard errors (plus `bias_allowance` of the reference, for a
// biased method) of the reference's.
void expect_agreement(const TransportOptions& options, int spp, int runs, double bias_allowance) {
  const testing::LoadedScene& c = testing::cornell_box<64, 64>();
  const std::vector<RegionEstimate> estimates = region_estimates(
      [&](std::uint64_t seed) { return render_method(c.scene, c.camera, options, spp, seed); }, kRegions, runs);
  for (size_t r = 0; r < std::size(kRegions); ++r) {
    const double expected = grey(mean_over(cornell_reference(), kRegions[r]));
    EXPECT_NEAR(estimates[r].mean, expected, 3.0 * estimates[r].standard_error + bias_allowance * expected)
        << method_name(options.method) << ", " << kRegionNames[r] << ": standard error "
        << estimates[r].standard_error;
    // The error bar is a real one: neither zero (a render that ignored its seed) nor so wide that
    // any answer passes.
    EXPECT_GT(estimates[r].standard_error, 0.0) << kRegionNames[r];
    EXPECT_LT(estimates[r].standard_error, 0.02 * expected) << kRegionNames[r];
  }
}

TEST(CornellAgreement, LightTracingFindsTheReference) { expect_agreement(method(TransportMethod::lt), 8, 16, 0.0); }

TEST(CornellAgreement, BidirectionalPathTracingFindsTheReference) {
  expect_agreement(method(TransportMethod::bdpt), 4, 16, 0.0);
}

TEST(CornellAgreement, ProgressivePhotonMappingFindsTheReferenceWithinItsBias) {
  TransportOptions options = method(TransportMethod::sppm);
  options.sppm.photons_per_pass = 20000;
  expect_agreement(options, 16, 16, 0.02);
}

}  // namespace
}  // namespace rt
