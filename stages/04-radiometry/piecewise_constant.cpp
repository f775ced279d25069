#include "04-radiometry/piecewise_constant.h"

#include "common/task.h"

#include <algorithm>
#include <cmath>

namespace rt {
namespace {

std::vector<float> or_uniform(std::span<const float> values) {
  const bool any = std::any_of(values.begin(), values.end(), [](float v) { return v > 0.0f; });
  return any ? std::vector<float>(values.begin(), values.end()) : std::vector<float>(values.size(), 1.0f);
}

// The largest float below 1: where x = (i + du) / n, rounded, would reach 1.
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

}  // namespace

PiecewiseConstant1D::PiecewiseConstant1D(std::span<const float> values) : bins_(or_uniform(values)) {
  double sum = 0.0;
  for (const float v : values) sum += double(v);
  integral_ = values.empty() ? 0.0f : float(sum / double(values.size()));
}

PiecewiseConstant1D::Sample PiecewiseConstant1D::sample(float u) const {
  // BEGIN TASK stage4.env.piecewise_1d
  const DiscreteDistribution::Choice choice = bins_.sample(u);
  const float du = std::clamp(float((double(u) - bins_.cumulative_below(choice.index)) / double(choice.pmf)), 0.0f, 1.0f);
  const float x = std::min((float(choice.index) + du) / float(size()), kOneMinusEpsilon);
  return Sample{x, choice.pmf * float(size()), choice.index};
  // PLACEHOLDER
  // report_unfinished_task("stage4.env.piecewise_1d");
  // (void)kOneMinusEpsilon;
  // return Sample{u, 1.0f, std::min(int(u * float(size())), size() - 1)};  // uniform: ignores the values
  // END TASK
}

float PiecewiseConstant1D::pdf(float x) const {
  if (!(x >= 0.0f && x < 1.0f)) return 0.0f;
  const int bin = std::min(int(x * float(size())), size() - 1);
  return bins_.pmf(bin) * float(size());
}

PiecewiseConstant2D::PiecewiseConstant2D(std::span<const float> values, int columns, int rows)
    : marginal_([&] {
        std::vector<float> row_integrals;
        for (int t = 0; t < rows; ++t) {
          conditional_.emplace_back(values.subspan(size_t(t) * size_t(columns), size_t(columns)));
          row_integrals.push_back(conditional_.back().integral());
        }
        return PiecewiseConstant1D(row_integrals);
      }()) {}

PiecewiseConstant2D::Sample PiecewiseConstant2D::sample(Vec2 u) const {
  const PiecewiseConstant1D::Sample t = marginal_.sample(u.y);
  const PiecewiseConstant1D::Sample s = conditional_[size_t(t.bin)].sample(u.x);
  return Sample{Vec2(s.x, t.x), s.pdf * t.pdf};
}

float PiecewiseConstant2D::pdf(Vec2 st) const {
  const float pt = marginal_.pdf(st.y);
  if (pt == 0.0f) return 0.0f;
  const int row = std::min(int(st.y * float(conditional_.size())), int(conditional_.size()) - 1);
  return pt * conditional_[size_t(row)].pdf(st.x);
}

}  // namespace rt
