// Stage 6 on the Cornell box, where every method must agree: light tracing, BDPT and SPPM against
// stage 5's converged reference (assets/references/cornell-box-256.pfm, averaged down to 64 x 64),
// region by region, and the image the same bit for bit for any thread count.
#include "common/image_io.h"

#include "stage6/cornell_regions.h"
#include "stage6/loaded_scene.h"
#include "stage6/transport_estimates.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

void expect_agreement(const TransportOptions& options, int spp, int runs, double bias_allowance) {
  const testing::LoadedScene& c = testing::cornell_box<64, 64>();
  testing::expect_cornell_agreement(
      [&](std::uint64_t seed) { return render_method(c.scene, c.camera, options, spp, seed); }, runs, bias_allowance,
      method_name(options.method));
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
