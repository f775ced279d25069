// Stage 4: piecewise-constant densities, the way to importance sample a function known only as a
// table (an environment map's texels). In 1D, n values f_i over n equal bins of [0, 1) define the
// density p(x) = f_i / I for x in bin i, with I = (1/n) sum f_i its integral. Sampling it is a
// discrete choice followed by a uniform position: choose bin i with probability P_i = f_i / sum f
// (04-radiometry/discrete_distribution.h inverts that CDF), then place x uniformly in the bin,
// reusing what is left of u: du = (u - P_0 - ... - P_{i-1}) / P_i, x = (i + du) / n, and
// p(x) = P_i n (Pharr, Jakob & Humphreys, "Physically Based Rendering", 4th ed., section A.4.1).
//
// In 2D a table f(s, t) of n_s x n_t values is sampled as p(s, t) = p(t) p(s | t): the marginal
// density of the row, p(t) proportional to the row's sum, then the row's own 1D density for s
// (the same book, section A.5.2). Its joint density is f(s, t) / I, I the integral over [0, 1)^2.
#pragma once

#include "04-radiometry/discrete_distribution.h"
#include "common/math.h"

#include <span>
#include <vector>

namespace rt {

class PiecewiseConstant1D {
 public:
  // Values must be finite and >= 0. All zero (nothing to prefer) gives the uniform density.
  explicit PiecewiseConstant1D(std::span<const float> values);

  struct Sample {
    float x;    // in [0, 1)
    float pdf;  // p(x), per unit length
    int bin;
  };
  // Task stage4.env.piecewise_1d. The x of u uniform in [0, 1): a bin by its probability, then the
  // rest of u spread uniformly over the bin.
  Sample sample(float u) const;
  float pdf(float x) const;  // 0 outside [0, 1)
  float integral() const { return integral_; }  // (1/n) sum f_i, before any all-zero fallback
  int size() const { return int(bins_.size()); }

 private:
  DiscreteDistribution bins_;
  float integral_ = 0.0f;
};

class PiecewiseConstant2D {
 public:
  // values[t_index * columns + s_index]: `rows` rows of `columns` values, row 0 at t in [0, 1 / rows).
  PiecewiseConstant2D(std::span<const float> values, int columns, int rows);

  struct Sample {
    Vec2 st;    // (s, t) in [0, 1)^2
    float pdf;  // p(s, t), per unit area of [0, 1)^2
  };
  Sample sample(Vec2 u) const;  // the row from u.y, the column within it from u.x
  float pdf(Vec2 st) const;

 private:
  std::vector<PiecewiseConstant1D> conditional_;  // per row, p(s | t)
  PiecewiseConstant1D marginal_;                  // p(t)
};

}  // namespace rt
