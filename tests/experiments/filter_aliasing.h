// Stage 1: the experiment behind the pixel filters' trade (docs/stage1.md, "Pixel reconstruction
// filters"): a zone plate, L(p) = 1/2 + 1/2 cos(pi k r^2) with r the distance in pixels from the
// image's centre, whose local frequency k r cycles per pixel grows linearly outwards. It crosses the
// pixels' Nyquist limit, 1/2 cycle per pixel, at r_N = 1 / (2k). An ideal (sinc) reconstruction
// would show the rings inside r_N unchanged and a flat 1/2 outside; a real filter keeps false rings
// outside (aliasing) and fades the true ones inside (blur). Used by tests/stage1/pixel_filter_test.cpp
// and by the chart program benchmarks/filter_aliasing.cpp.
#pragma once

#include "common/image.h"
#include "common/scene.h"

#include <cstdint>

namespace rt {

struct ZonePlateScores {
  // Mean of (I - 1/2)^2 over the pixels beyond 1.25 r_N, over that of the signal itself there (1/8):
  // the energy above Nyquist that folded back into the image. 0 for an ideal filter.
  double aliasing = 0.0;
  // Mean of (I - 1/2)^2 over the pixels within r_N / 2, over that of the signal at their centres:
  // how much of the passband survives. 1 for an ideal filter; a blurring filter gives less.
  double passband = 0.0;
  Image image;  // the render itself, for the handout's pictures
};

// Renders the zone plate with stage 1's pixel loop (a size x size image, spp samples per pixel,
// the given filter) and scores it. The plate reaches Nyquist at r_N = size / 4.
ZonePlateScores measure_zone_plate(PixelFilterType filter, int size, int spp, std::uint64_t seed);
// Its two halves: the render (what a graded test records) and the scores of a square render.
Image render_zone_plate(PixelFilterType filter, int size, int spp, std::uint64_t seed);
ZonePlateScores score_zone_plate(const Image& image);

}  // namespace rt
