// The least-squares slope of log(error) against log(samples): how fast an error falls with the
// work (-1/2 for an unbiased Monte Carlo estimator's RMSE). Shared by the convergence tests.
#pragma once

#include <cmath>
#include <vector>

namespace rt::testing {

inline double log_log_slope(const std::vector<double>& samples, const std::vector<double>& errors) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) {
    const double x = std::log(samples[i]), y = std::log(errors[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace rt::testing
