// The Cornell box regions the transport tests compare (stage 5's Cornell test's, each inside one
// surface) at 64 x 64, and stage 5's converged reference (assets/references/cornell-box-256.pfm)
// averaged down to that film. Shared by stage 6's and stage 7's tests.
#pragma once

#include "common/image.h"
#include "common/image_io.h"
#include "common/metrics.h"
#include "support/test_support.h"

namespace rt::testing {

inline const Image& cornell_reference_64() {
  static const Image reference = downsample(read_pfm(source_path("assets/references/cornell-box-256.pfm")), 4);
  return reference;
}

inline constexpr PixelRect kCornellRegions[] = {
    {36, 14, 46, 24}, {20, 57, 30, 61}, {4, 16, 11, 40}, {53, 16, 60, 40}, {14, 2, 50, 6}};
inline constexpr const char* kCornellRegionNames[] = {"back wall", "floor between the blocks", "red wall", "green wall",
                                                      "ceiling"};

}  // namespace rt::testing
