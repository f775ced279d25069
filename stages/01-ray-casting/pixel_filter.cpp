#include "01-ray-casting/pixel_filter.h"

#include "common/task.h"

#include <cmath>

namespace rt {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Gaussian: sigma 1/2, cut at 3 sigma and lowered by its value there, so it reaches 0 at the radius
// without a step (PBR 4th ed. section 8.8.4).
constexpr double kGaussSigma = 0.5;
double gaussian(double x) { return std::exp(-x * x / (2.0 * kGaussSigma * kGaussSigma)); }

// Mitchell-Netravali with B = C = 1/3 (their eq. 8). On [1, 2] the cubic factors as
// -(x - 2)^2 (7x - 8) / 18: negative on (8/7, 2), which is the lobe that sharpens.
constexpr double kMitchellZero = 8.0 / 7.0;
double mitchell(double x) {
  if (x < 1.0) return (7.0 * x * x * x - 12.0 * x * x + 16.0 / 3.0) / 6.0;
  return -(x - 2.0) * (x - 2.0) * (7.0 * x - 8.0) / 18.0;
}
// Antiderivatives: of the inner cubic, and of t^2 (7t + 6) with t = x - 2 (the outer one times -18).
double mitchell_inner_integral(double x) { return (1.75 * x * x * x * x - 4.0 * x * x * x + 16.0 / 3.0 * x) / 6.0; }
double mitchell_outer_antiderivative(double t) { return 1.75 * t * t * t * t + 2.0 * t * t * t; }

// Blackman-Harris four-term coefficients (Harris 1978, table 1, the -92 dB window).
constexpr double kBh[4] = {0.35875, 0.48829, 0.14128, 0.01168};

}  // namespace

PixelFilter::PixelFilter(PixelFilterType type) : type_(type) {
  switch (type) {
    case PixelFilterType::box: radius_ = 0.5; break;
    case PixelFilterType::tent: radius_ = 1.0; break;
    case PixelFilterType::gaussian: radius_ = 1.5; break;
    case PixelFilterType::mitchell:
    case PixelFilterType::blackman_harris: radius_ = 2.0; break;
  }
  abs_area_ = 2.0 * abs_integral(radius_);
  // Knot k: where the integral of |f1| from 0 reaches k / K of its half.
  inverse_[0] = 0.0;
  inverse_[kInverseKnots] = radius_;
  for (int k = 1; k < kInverseKnots; ++k)
    inverse_[size_t(k)] = solve_abs_integral(0.5 * abs_area_ * k / kInverseKnots, inverse_[size_t(k) - 1], radius_,
                                             0.5 * (inverse_[size_t(k) - 1] + radius_));
  // Only Mitchell is ever negative; its signed integral over [-2, 2] is 1 (Mitchell and Netravali
  // chose the cubics so: a flat field stays flat).
  signed_area_ = has_negative_lobes() ? 1.0 : abs_area_;
}

double PixelFilter::profile(double x) const {
  x = std::abs(x);
  if (!(x <= radius_)) return 0.0;
  switch (type_) {
    case PixelFilterType::box: return 1.0;
    case PixelFilterType::tent: return 1.0 - x;
    case PixelFilterType::gaussian: return gaussian(x) - gaussian(radius_);
    case PixelFilterType::mitchell: return mitchell(x);
    case PixelFilterType::blackman_harris: {
      const double a = kPiD * x / radius_;
      return kBh[0] + kBh[1] * std::cos(a) + kBh[2] * std::cos(2.0 * a) + kBh[3] * std::cos(3.0 * a);
    }
  }
  return 0.0;
}

double PixelFilter::abs_integral(double x) const {
  switch (type_) {
    case PixelFilterType::box: return x;
    case PixelFilterType::tent: return x - 0.5 * x * x;
    case PixelFilterType::gaussian:
      // integral of exp(-t^2 / (2 sigma^2)) from 0 to x = sigma sqrt(pi/2) erf(x / (sigma sqrt 2)).
      return kGaussSigma * std::sqrt(0.5 * kPiD) * std::erf(x / (kGaussSigma * std::sqrt(2.0))) -
             x * gaussian(radius_);
    case PixelFilterType::mitchell: {
      if (x <= 1.0) return mitchell_inner_integral(x);
      const double inner = mitchell_inner_integral(1.0);
      const double start = mitchell_outer_antiderivative(-1.0);
      if (x <= kMitchellZero) return inner - (mitchell_outer_antiderivative(x - 2.0) - start) / 18.0;
      const double zero = mitchell_outer_antiderivative(kMitchellZero - 2.0);
      return inner - (zero - start) / 18.0 + (mitchell_outer_antiderivative(x - 2.0) - zero) / 18.0;
    }
    case PixelFilterType::blackman_harris: {
      const double a = kPiD * x / radius_;
      return kBh[0] * x + radius_ / kPiD *
                              (kBh[1] * std::sin(a) + kBh[2] / 2.0 * std::sin(2.0 * a) + kBh[3] / 3.0 * std::sin(3.0 * a));
    }
  }
  return 0.0;
}

double PixelFilter::pdf(Vec2 s) const { return std::abs(evaluate(s)) / (abs_area_ * abs_area_); }

Vec2 PixelFilter::invert(Vec2 s) const {
  auto cdf = [&](double x) {
    const double inside = std::min(std::abs(x), radius_);
    return 0.5 + std::copysign(abs_integral(inside), x) / abs_area_;
  };
  return Vec2(float(cdf(s.x)), float(cdf(s.y)));
}

double PixelFilter::solve_abs_integral(double target, double lo, double hi, double x) const {
  // Newton's step x - (A(x) - target) / |f1(x)| where it stays inside the bracket, else bisection;
  // each step also shrinks the bracket, since A is increasing. Stops once a step moves x by less
  // than 1e-9 pixels, far below a float offset's resolution (1.2e-7 at 1 pixel).
  for (int i = 0; i < 60; ++i) {
    const double excess = abs_integral(x) - target;
    if (excess == 0.0) break;
    (excess < 0.0 ? lo : hi) = x;
    const double slope = std::abs(profile(x));
    const double newton = slope > 0.0 ? x - excess / slope : lo;
    const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    const bool converged = std::abs(next - x) <= 1e-9;
    x = next;
    if (converged) break;
  }
  return x;
}

double PixelFilter::inverse_abs_integral(double t) const {
  // The table brackets the answer between two knots; their chord is the first guess, off by a
  // small fraction of a knot's gap, so Newton needs a step or two instead of about six from a
  // blind guess. Measured by benchmarks/filter_aliasing (a zone plate, 256 x 256 at 256 spp, the
  // box's render 1.1-1.3 s in the same run): the Gaussian's render took 6.8 s with the blind guess
  // and a 1e-12 tolerance, 3.5 s with the table and 1e-9; Blackman-Harris's 9.4 s, 4.8 s.
  const double scaled = t * kInverseKnots;
  const int i = std::min(int(scaled), kInverseKnots - 1);
  const double lo = inverse_[size_t(i)], hi = inverse_[size_t(i) + 1];
  return solve_abs_integral(t * 0.5 * abs_area_, lo, hi, lo + (scaled - i) * (hi - lo));
}

FilterSample PixelFilter::sample(Vec2 u) const {
  // BEGIN TASK stage1.filter.sample
  if (type_ == PixelFilterType::box) return FilterSample{u, 1.0f};
  // One axis: |s| = A^-1(|2u - 1| abs_area / 2), on u's side of 1/2.
  auto sample_axis = [&](float ui) {
    const double magnitude = inverse_abs_integral(std::abs(2.0 * double(ui) - 1.0));
    return ui < 0.5f ? -magnitude : magnitude;
  };
  const double sx = sample_axis(u.x), sy = sample_axis(u.y);
  const Vec2 film_offset(0.5f + float(sx), 0.5f + float(sy));
  if (!has_negative_lobes()) return FilterSample{film_offset, 1.0f};  // p is proportional to f: w = 1
  const double ratio = abs_area_ / signed_area_;
  return FilterSample{film_offset, float(std::copysign(ratio * ratio, profile(sx) * profile(sy)))};
  // PLACEHOLDER
  // report_unfinished_task("stage1.filter.sample");
  // return FilterSample{u, 1.0f};  // the box filter, whatever the type
  // END TASK
}

}  // namespace rt
