// Image error metrics used by tests, benchmarks and grading. All of them average over every pixel
// and every RGB channel, so one number compares two images of the same size.
#pragma once

#include "common/image.h"

namespace rt {

// Mean squared error: mean of (a - b)^2.
double mse(const Image& image, const Image& reference);
double rmse(const Image& image, const Image& reference);
// The RMSE over the pixels of `rect` alone (the region a scene is about: a caustic, a wall).
// Throws std::invalid_argument for images of different sizes or a rectangle outside them.
double rmse(const Image& image, const Image& reference, PixelRect rect);

// Relative MSE: mean of (a - b)^2 / (b^2 + epsilon). Dividing by the reference's own value
// weighs dark and bright regions alike; epsilon keeps black reference pixels from dominating
// (0.01 is the customary value, as in Rousselle et al. 2011 and pbrt-v4's imgtool).
double relative_mse(const Image& image, const Image& reference, double epsilon = 1e-2);

// Mean colour over a rectangle (e.g. a wall of the Cornell box).
DVec3 mean_over(const Image& image, PixelRect rect);

// Each `factor` x `factor` block averaged into one pixel. With a box pixel filter this is exact
// for expectations: a pixel of the small image integrates the same footprint as the block it
// replaces, so a 256 x 256 reference downsampled by 4 is the reference of a 64 x 64 render.
// Throws std::invalid_argument unless `factor` divides both sides.
Image downsample(const Image& image, int factor);

}  // namespace rt
