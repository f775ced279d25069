// Chi-square goodness-of-fit tests for samplers, in the manner of pbrt-v4's and Mitsuba 3's
// sampling tests: draw many samples, histogram them, integrate the claimed pdf over every bin to
// get the expected counts, pool sparse bins, and reject if Pearson's statistic is improbable.
// Fixed seeds make each test deterministic; the significance level is corrected for the number of
// chi-square tests in the suites that use it (Sidak), so the family as a whole has a 1% false-alarm
// rate while each test still rejects a wrong pdf (see DistributionTest.RejectsAWrongPdf).
#pragma once

#include "common/math.h"
#include "common/random.h"
#include "support/subject.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace rt::testing {

// pi in double: grid edges in float pi would put pi/2 a little below the horizon.
inline constexpr double kPiD = 3.14159265358979323846;
inline constexpr double kHalfPi = 0.5 * kPiD;

// Bins are integrated by composite Simpson with 32 x 32 intervals each: pdfs with a kink (the
// visible-normal cutoff wo . m = 0, the Phong lobe at n = 1) need that many to be exact enough
// for a million samples.

// Upper bound on the number of chi-square tests in the suites that use this file (stages 1 and 4):
// the family for the correction.
inline constexpr int kChiSquareFamilySize = 64;
inline constexpr double kFamilySignificance = 0.01;

// Regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a): the power series
// for x < a + 1 and Legendre's continued fraction otherwise (Abramowitz & Stegun 6.5.29, 6.5.31),
// the latter by the modified Lentz method.
inline double regularized_gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefix = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000 && std::abs(term) > 1e-16 * std::abs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return 1.0 - std::exp(log_prefix) * sum;
  }
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-15) break;
  }
  return std::exp(log_prefix) * h;
}

// P(X >= statistic) for X chi-square distributed with `dof` degrees of freedom.
inline double chi_square_p_value(double statistic, int dof) { return regularized_gamma_q(0.5 * dof, 0.5 * statistic); }

struct ChiSquareResult {
  bool passed;
  double statistic, p_value, threshold;
  int dof;
  std::string message;
};

// Pearson's test of observed bin counts against expected ones. Bins expecting fewer than
// `min_expected` samples are pooled into one (the chi-square approximation needs about 5 per bin);
// any sample in a bin whose expected count is 0 fails at once (a sample where the pdf says none
// can be).
inline ChiSquareResult chi_square_test(const std::vector<double>& observed, const std::vector<double>& expected,
                                       double min_expected = 5.0) {
  const double threshold = 1.0 - std::pow(1.0 - kFamilySignificance, 1.0 / kChiSquareFamilySize);
  std::vector<size_t> order(observed.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  double statistic = 0.0, pooled_observed = 0.0, pooled_expected = 0.0;
  int bins = 0;
  for (const size_t i : order) {
    if (expected[i] == 0.0) {
      if (observed[i] > 0.0) {
        std::ostringstream s;
        s << observed[i] << " samples in bin " << i << " where the pdf is 0";
        return {false, kInfinity, 0.0, threshold, 0, s.str()};
      }
      continue;
    }
    if (expected[i] < min_expected) {
      pooled_observed += observed[i];
      pooled_expected += expected[i];
      continue;
    }
    if (pooled_expected > 0.0 && pooled_expected < min_expected) {
      pooled_observed += observed[i];  // top the pool up with the smallest regular bins
      pooled_expected += expected[i];
      continue;
    }
    statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pooled_expected > 0.0) {
    statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++bins;
  }
  const int dof = bins - 1;
  const double p = dof > 0 ? chi_square_p_value(statistic, dof) : 1.0;
  std::ostringstream s;
  s << "chi^2 = " << statistic << " with " << dof << " degrees of freedom, p = " << p << " (reject below "
    << threshold << ")";
  return {p >= threshold, statistic, p, threshold, dof, s.str()};
}

// Composite Simpson weights for n (even) intervals over [a, b]: the nodes and their weights.
inline void simpson_nodes(double a, double b, int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(size_t(n) + 1);
  w.resize(size_t(n) + 1);
  const double h = (b - a) / n;
  for (int i = 0; i <= n; ++i) {
    x[size_t(i)] = i == n ? b : a + i * h;  // the last node exactly at b
    w[size_t(i)] = h / 3.0 * (i == 0 || i == n ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
}

// The integral of g(u, v) over [u0, u1] x [v0, v1] by composite Simpson with n x n intervals.
inline double integrate_2d(const std::function<double(double, double)>& g, double u0, double u1, double v0, double v1,
                           int n) {
  std::vector<double> xu, wu, xv, wv;
  simpson_nodes(u0, u1, n, xu, wu);
  simpson_nodes(v0, v1, n, xv, wv);
  double sum = 0.0;
  for (size_t i = 0; i < xu.size(); ++i)
    for (size_t j = 0; j < xv.size(); ++j) sum += wu[i] * wv[j] * g(xu[i], xv[j]);
  return sum;
}

inline Vec3 direction_from_angles(double theta, double phi) {
  return Vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
}

// Bins on (part of) the sphere of directions: theta in [theta_min, theta_max] from +z, phi in
// [0, 2 pi), each cut into equal steps; dw = sin(theta) dtheta dphi.
struct SphereGrid {
  int theta_bins = 20, phi_bins = 40;
  double theta_min = 0.0, theta_max = kPiD;

  size_t size() const { return size_t(theta_bins) * size_t(phi_bins); }
  std::optional<size_t> bin(Vec3 w) const {
    const double theta = std::acos(std::clamp(double(w.z) / glm::length(DVec3(w)), -1.0, 1.0));
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0.0) phi += 2.0 * kPiD;
    if (theta < theta_min || theta > theta_max) return std::nullopt;
    const int i = std::min(theta_bins - 1, int((theta - theta_min) / (theta_max - theta_min) * theta_bins));
    const int j = std::min(phi_bins - 1, int(phi / (2.0 * kPiD) * phi_bins));
    return size_t(i) * size_t(phi_bins) + size_t(j);
  }
  // The expected count of every bin for `samples` draws from a density `pdf` over solid angle.
  std::vector<double> expected(const std::function<double(Vec3)>& pdf, double samples, int simpson = 32) const {
    std::vector<double> e(size());
    const double dt = (theta_max - theta_min) / theta_bins, dp = 2.0 * kPiD / phi_bins;
    for (int i = 0; i < theta_bins; ++i)
      for (int j = 0; j < phi_bins; ++j)
        e[size_t(i) * size_t(phi_bins) + size_t(j)] =
            samples * integrate_2d([&](double t, double p) { return pdf(direction_from_angles(t, p)) * std::sin(t); },
                                   theta_min + i * dt, theta_min + (i + 1) * dt, j * dp, (j + 1) * dp, simpson);
    return e;
  }
};

// Draws `samples` directions (a sampler may return nothing: a wasted sample, not binned) and
// counts them per bin; a direction outside the grid's theta range counts as bin "outside" and
// fails the test through an extra bin expecting 0.
inline std::vector<double> histogram(const SphereGrid& grid, int samples, std::uint64_t seed,
                                     const std::function<std::optional<Vec3>(Rng&)>& sampler) {
  std::vector<double> counts(grid.size() + 1, 0.0);
  Rng rng(seed, 0, 0);
  for (int k = 0; k < samples; ++k)
    if (const std::optional<Vec3> w = sampler(rng)) {
      const std::optional<size_t> b = grid.bin(*w);
      counts[b ? *b : grid.size()] += 1.0;
    }
  return counts;
}

// The whole test for a direction sampler against its claimed density. The sampler and the density
// are the submission's: the histogram and the expected counts are made inside subject(), the
// verdict outside.
inline ChiSquareResult sphere_chi_square(const SphereGrid& grid, int samples, std::uint64_t seed,
                                         const std::function<std::optional<Vec3>(Rng&)>& sampler,
                                         const std::function<double(Vec3)>& pdf) {
  auto [observed, expected] =
      subject([&] { return std::pair(histogram(grid, samples, seed, sampler), grid.expected(pdf, samples)); });
  expected.push_back(0.0);  // the "outside" bin
  return chi_square_test(observed, expected);
}

}  // namespace rt::testing
