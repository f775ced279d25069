// Stage 1: pixel reconstruction filters, and the task of sampling them, stage1.filter.sample.
//
// Why a pixel is an average (the lecture's closing question). A pixel is not a point of the film
// but a small area of it, and what a display shows there should be the radiance reaching the film
// around the pixel's centre c, weighted by a filter f (Mitchell and Netravali, "Reconstruction
// Filters in Computer Graphics", SIGGRAPH 1988; PBR 4th ed. section 8.8):
//   I(c) = integral f(s) L(c + s) ds / integral f(s) ds.
// The box filter (f = 1 over the pixel) makes that the plain average of the radiance over the
// pixel; wider filters trade aliasing (detail finer than the pixels folding into false patterns)
// against blur, and filters with negative lobes (Mitchell) sharpen edges at the cost of ringing.
//
// Filter importance sampling (Ernst et al., "Filter Importance Sampling", IEEE RT 2006; pbrt-v4's
// film): draw the offset s from a density p proportional to |f| and weight the sample by
//   w(s) = f(s) / (p(s) integral f) = sign(f(s)) * integral |f| / integral f,
// so that I(c) ~= (1/N) sum_k w_k L(c + s_k) is unbiased. Every sample still belongs to its own
// pixel, so renders stay the same bit for bit for any thread count and sample batches add up
// exactly, which splatting each sample into its neighbours would not give. For a filter that is
// never negative, p is proportional to f and w = 1 exactly: the pixel is the plain mean of its
// samples, as with the box. Mitchell's negative lobes give w = -c^2 where f(s) < 0 (c = the
// ratio above per axis, 1.0700): the sign is what carries the sharpening, and the pixel is still
// unbiased; a constant scene gives the constant times the mean weight, which tends to 1
// (docs/stage1.md, "Pixel reconstruction filters", measures all of this).
//
// Every filter here is separable, f(x, y) = f1(x) f1(y), and symmetric, so it is sampled one axis at
// a time by inverting the cumulative integral of |f1|, given in closed form per filter.
#pragma once

#include "common/math.h"
#include "common/scene.h"

#include <array>

namespace rt {

struct FilterSample {
  // Where the sample lies, from the pixel's top-left corner in pixel units: the film point is
  // (x, y) + film_offset. For the box this is u itself (the same bits as stage 1 always had);
  // for the others (0.5, 0.5) + s, s the offset from the pixel's centre.
  Vec2 film_offset;
  // f(s) / (p(s) integral f): 1 for every filter that is never negative.
  float weight;
};

class PixelFilter {
 public:
  // The shapes (radius r in pixels, f1 on [-r, r]):
  //   box              r = 1/2  f1 = 1
  //   tent             r = 1    f1 = 1 - |x|
  //   gaussian         r = 3/2  f1 = exp(-x^2 / (2 sigma^2)) - exp(-r^2 / (2 sigma^2)), sigma = 1/2
  //   mitchell         r = 2    Mitchell-Netravali cubic with B = C = 1/3 (their recommended pair)
  //   blackman_harris  r = 2    a0 + a1 cos(pi x / r) + a2 cos(2 pi x / r) + a3 cos(3 pi x / r),
  //                             the four-term window of Harris ("On the Use of Windows for Harmonic
  //                             Analysis with the Discrete Fourier Transform", Proc. IEEE 1978)
  explicit PixelFilter(PixelFilterType type);

  PixelFilterType type() const { return type_; }
  double radius() const { return radius_; }
  bool has_negative_lobes() const { return type_ == PixelFilterType::mitchell; }

  // f1(x), the filter's profile along one axis (0 beyond the radius), and f(s) = f1(s_x) f1(s_y).
  double profile(double x) const;
  double evaluate(Vec2 s) const { return profile(s.x) * profile(s.y); }
  // The integral of |f1| from 0 to x, for 0 <= x <= radius; in closed form for every filter.
  double abs_integral(double x) const;
  // The integrals of |f1| and of f1 over [-r, r].
  double abs_area() const { return abs_area_; }
  double signed_area() const { return signed_area_; }

  // The density sample() draws s from: |f(s)| / abs_area()^2, per unit area of the film (pixels^2).
  double pdf(Vec2 s) const;

  // The x in [0, radius] where abs_integral(x) = t abs_area() / 2, for t in [0, 1]: the inverse of
  // the half-axis cumulative distribution, by Newton's method kept inside a bracket that a table of
  // the inverse at 65 knots (built once per filter) gives.
  double inverse_abs_integral(double t) const;

  // Task stage1.filter.sample. The sample for uniform numbers u in [0, 1)^2 by inversion (PBR 4th
  // ed. section 2.3): along each axis s = F^-1(u), F the cumulative distribution of
  // |f1| / abs_area(),
  //   F(s) = 1/2 + sign(s) abs_integral(|s|) / abs_area(),
  // so |s| = inverse_abs_integral(|2u - 1|), negative for u < 1/2; and the weight
  // sign(f(s)) (abs_area() / signed_area())^2. The box returns u itself and 1.
  FilterSample sample(Vec2 u) const;
  // The u that sample() maps to offset s (from the pixel's centre): the cumulative distribution
  // itself, per axis. What the tests use to check that sample() inverts it.
  Vec2 invert(Vec2 s) const;

 private:
  // Newton's method for abs_integral(x) = target from x, kept inside [lo, hi].
  double solve_abs_integral(double target, double lo, double hi, double x) const;

  static constexpr int kInverseKnots = 64;
  PixelFilterType type_;
  double radius_;
  double abs_area_ = 0.0, signed_area_ = 0.0;
  std::array<double, kInverseKnots + 1> inverse_{};
};

}  // namespace rt
