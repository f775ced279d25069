// The Cornell box regions the transport tests compare (stage 5's Cornell test's, each inside one
// surface) at 64 x 64, and stage 5's converged reference (assets/references/cornell-box-256.pfm)
// averaged down to that film, and the check that a method finds it. Shared by stage 6's and stage
// 7's tests.
#pragma once

#include "common/image.h"
#include "common/image_io.h"
#include "common/metrics.h"
#include "stage6/transport_estimates.h"
#include "support/test_support.h"

#include <functional>
#include <string>

namespace rt::testing {

inline const Image& cornell_reference_64() {
  static const Image reference = downsample(read_pfm(source_path("assets/references/cornell-box-256.pfm")), 4);
  return reference;
}

inline constexpr PixelRect kCornellRegions[] = {
    {36, 14, 46, 24}, {20, 57, 30, 61}, {4, 16, 11, 40}, {53, 16, 60, 40}, {14, 2, 50, 6}};
inline constexpr const char* kCornellRegionNames[] = {"back wall", "floor between the blocks", "red wall", "green wall",
                                                      "ceiling"};

// Region means of `runs` renders (seeds 1 ... runs) against the reference: every region within 3
// standard errors (plus `bias_allowance` of the reference, for a biased method), and each error
// bar a real one: neither zero (a render that ignored its seed) nor so wide that any answer
// passes (under 2 % of the reference).
inline void expect_cornell_agreement(const std::function<Image(std::uint64_t)>& render, int runs, double bias_allowance,
                                     const std::string& what) {
  const std::vector<RegionEstimate> estimates = region_estimates(render, kCornellRegions, runs);
  for (size_t r = 0; r < std::size(kCornellRegions); ++r) {
    const double expected = grey(mean_over(cornell_reference_64(), kCornellRegions[r]));
    EXPECT_NEAR(estimates[r].mean, expected, 3.0 * estimates[r].standard_error + bias_allowance * expected)
        << what << ", " << kCornellRegionNames[r] << ": standard error " << estimates[r].standard_error;
    EXPECT_GT(estimates[r].standard_error, 0.0) << what << ", " << kCornellRegionNames[r];
    EXPECT_LT(estimates[r].standard_error, 0.02 * expected) << what << ", " << kCornellRegionNames[r];
  }
}

}  // namespace rt::testing
