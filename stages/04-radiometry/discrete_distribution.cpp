#include "04-radiometry/discrete_distribution.h"

#include "common/task.h"

#include <algorithm>

namespace rt {

DiscreteDistribution::DiscreteDistribution(std::span<const float> weights) {
  cdf_.reserve(weights.size());
  for (const float w : weights) {
    total_ += double(std::max(0.0f, w));
    cdf_.push_back(total_);
  }
}

DiscreteDistribution::Choice DiscreteDistribution::sample(float u) const {
  // BEGIN TASK stage4.light.choose_by_power
  const double target = double(u) * total_;
  const auto found = std::upper_bound(cdf_.begin(), cdf_.end(), target);
  // u < 1 keeps target below the total; the clamp guards the last item against rounding.
  const int index = int(std::min<std::ptrdiff_t>(found - cdf_.begin(), std::ptrdiff_t(cdf_.size()) - 1));
  return Choice{index, pmf(index)};
  // PLACEHOLDER
  // report_unfinished_task("stage4.light.choose_by_power");
  // (void)u;
  // return Choice{0, pmf(0)};
  // END TASK
}

double DiscreteDistribution::cumulative_below(int index) const {
  if (index <= 0 || cdf_.empty() || total_ == 0.0) return 0.0;
  return cdf_[std::min(size_t(index), cdf_.size()) - 1] / total_;
}

float DiscreteDistribution::pmf(int index) const {
  if (index < 0 || size_t(index) >= cdf_.size() || total_ == 0.0) return 0.0f;
  const double below = index == 0 ? 0.0 : cdf_[size_t(index) - 1];
  return float((cdf_[size_t(index)] - below) / total_);
}

}  // namespace rt
