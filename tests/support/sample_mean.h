// The mean of independent samples and its standard error, for every Monte Carlo test that checks a
// mean against a closed form or a reference within a few standard errors: the sample variance
// s^2 = (sum v^2 - n m^2) / (n - 1) (unbiased), and the standard error of the mean sqrt(s^2 / n).
#pragma once

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rt::testing {

struct Estimate {
  double mean = 0.0, standard_error = 0.0;
};
inline auto record_fields(Estimate& e) { return std::tie(e.mean, e.standard_error); }  // support/record.h

class SampleMean {
 public:
  void add(double v) {
    sum_ += v;
    sum2_ += v * v;
    ++count_;
  }
  long count() const { return count_; }
  double mean() const { return sum_ / double(count_); }
  // Needs two samples or more; a negative variance from rounding is taken as zero.
  double standard_error() const {
    const double m = mean(), n = double(count_);
    return std::sqrt(std::max(0.0, (sum2_ - n * m * m) / (n - 1.0)) / n);
  }
  Estimate estimate() const { return {mean(), standard_error()}; }

 private:
  double sum_ = 0.0, sum2_ = 0.0;
  long count_ = 0;
};

}  // namespace rt::testing
