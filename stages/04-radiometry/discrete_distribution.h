// Stage 4: choosing one of n items with probability proportional to a weight, e.g. one emitter
// among many by its power, so that bright lights get the samples. The estimator divides by the
// probability of the choice, so it stays unbiased for any weights that are positive wherever the
// integrand is not zero.
#pragma once

#include <span>
#include <vector>

namespace rt {

class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  // Weights must be finite and >= 0; items of weight 0 are never chosen.
  explicit DiscreteDistribution(std::span<const float> weights);

  struct Choice {
    int index;
    float pmf;  // the probability of having chosen it
  };

  // Task stage4.light.choose_by_power. Inverts the cumulative distribution: the first item whose
  // cumulative weight exceeds u times the total (binary search), for u uniform in [0, 1).
  Choice sample(float u) const;
  float pmf(int index) const;
  // The probability of the items before `index`, P(0) + ... + P(index - 1): where its interval of
  // u starts.
  double cumulative_below(int index) const;
  size_t size() const { return cdf_.size(); }
  bool empty() const { return cdf_.empty() || total_ == 0.0; }

 private:
  std::vector<double> cdf_;  // cdf_[i] = w_0 + ... + w_i, in double so long sums stay exact enough
  double total_ = 0.0;
};

}  // namespace rt
