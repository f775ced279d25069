#include "07-vcm-mlt/vcm_budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rt {

namespace {

// Costs per unit of work, in the time of one camera subpath vertex (its ray and BSDF sample, its
// record, and the weights of the light it hits), fitted by least squares to the time per iteration
// of each budget on the five scenes of the chart (128 x 96 pixels, 16 iterations, one thread,
// benchmarks/fit_vcm_costs.py): the mean of two fits, whose single costs differ by up to 3x (the
// counts come in nearly fixed proportions) while the times they predict do not. Measured a third
// time, these predict 0.78 to 1.16 of each budget's time (docs/stage7.md, section 5). A light
// subpath's start (its random numbers' stream, a light and a point on it) costs about what its
// vertices do; a light vertex and its link to the camera come in equal numbers, so the fit splits
// their cost evenly.
constexpr double kCostCameraVertex = 1.0;
constexpr double kCostLightPoint = 0.12;
constexpr double kCostLightSubpath = 0.5;
constexpr double kCostLightVertex = 0.215;
constexpr double kCostCameraLink = 0.215;
constexpr double kCostConnection = 0.26;
constexpr double kCostMerge = 0.75;
constexpr double kCostPhoton = 0.33;  // a light vertex put in the grid
// Without light subpaths the camera subpaths are stage 5's path tracer: per camera vertex and
// light point, measured the same way, 0.39 to 0.47 camera vertices of VCM's.
constexpr double kCostPathTracerVertex = 0.42;

}  // namespace

std::string describe(const VcmBudget& b) {
  if (b.light_paths == 0) return "no light subpaths (path tracing)";
  const char* merges = b.merge == Merging::none           ? "no merges"
                       : b.merge == Merging::where_needed ? "merges where only they reach"
                                                          : "merges everywhere";
  return std::to_string(b.light_paths) + (b.light_paths == 1 ? " light subpath" : " light subpaths") + " a pixel, " +
         (b.connect ? "connections" : "no connections") + ", " + merges;
}

std::string budget_word(const VcmBudget& b) {
  if (b == kEveryTechnique) return "all";
  if (b.light_paths == 0) return "pt";
  return std::to_string(b.light_paths) + (b.connect ? "c" : "") + (b.merge != Merging::none ? "m" : "");
}

VcmTechniques techniques_within(VcmTechniques all, const VcmBudget& b) {
  const bool light = b.light_paths > 0;
  all.light_trace = all.light_trace && light;
  all.connect = all.connect && light && b.connect;
  all.merge = all.merge && light && b.merge != Merging::none;
  all.light_paths *= float(b.light_paths);
  all.eta *= float(b.light_paths);
  return all;
}

VcmTechniques techniques_on_path(std::span<const PathDensity> path, Technique made_by, VcmTechniques on) {
  if (!on.merge) return on;
  // A connection other than the light hit made it, or could have.
  const int k = int(path.size()) - 1;
  bool connectable = made_by.kind == Technique::connection && made_by.t <= k;
  if (!connectable) {
    VcmTechniques connections = on;
    connections.hit_light = connections.merge = false;
    connectable = technique_densities(path, made_by, connections).sum > 0.0;
  }
  on.merge = !connectable;
  return on;
}

double iteration_cost(const VcmWork& work, const VcmBudget& b, double camera_samples) {
  const double camera = double(work.camera_vertices), light_points = double(work.light_points);
  if (b.light_paths == 0) return camera_samples * kCostPathTracerVertex * (camera + light_points);
  const double per_light_path = double(b.light_paths);
  double camera_side = kCostCameraVertex * camera + kCostLightPoint * light_points;
  double light_side = kCostLightSubpath * double(work.light_subpaths) + kCostLightVertex * double(work.light_vertices) +
                      kCostCameraLink * double(work.camera_links);
  if (b.connect) camera_side += kCostConnection * double(work.connections);
  if (b.merge != Merging::none) {
    const MergeWork& m = b.connect ? work.with_connections : work.without_connections;
    camera_side += per_light_path * kCostMerge * double(m.merges);
    light_side += kCostPhoton * double(m.photons);
  }
  return camera_samples * camera_side + per_light_path * light_side;
}

BudgetTerms budget_terms(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& first,
                         Color value) {
  BudgetTerms terms;
  const double squared = double(glm::dot(value, value));
  if (!(squared > 0.0) || !std::isfinite(squared)) return terms;  // the image drops such a sample too
  const TechniqueDensities taken = technique_densities(path, made_by, techniques_on_path(path, made_by, first));
  if (!(taken.sum > 0.0) || !(taken.own > 0.0)) return terms;
  // (f / q_1)^2 q_1, each density relative to the same connection's: f = value n p.
  terms.balance_squared = squared * taken.own * taken.own / taken.sum;
  for (size_t b = 0; b < kVcmBudgetCount; ++b) {
    VcmTechniques on = techniques_on_path(path, made_by, techniques_within(first, kVcmBudgets[b]));
    const double all = technique_densities(path, made_by, on).sum;
    on.light_paths = 0.0f;  // light tracing's samples: none
    terms.camera[b] = technique_densities(path, made_by, on).sum;
    terms.light[b] = all - terms.camera[b];
  }
  return terms;
}

void add_budget_moments(const BudgetTerms& terms, std::span<double> sums) {
  if (!(terms.balance_squared > 0.0)) return;
  for (size_t b = 0; b < kVcmBudgetCount; ++b)
    for (size_t c = 0; c < kCameraSampleChoices; ++c) {
      const double q = double(kCameraSampleCounts[c]) * terms.camera[b] + terms.light[b];
      sums[b * kCameraSampleChoices + c] +=
          q > 0.0 ? terms.balance_squared / q : std::numeric_limits<double>::infinity();
    }
}

BudgetPlan plan_budget(std::span<const double> pixel_moments, const VcmWork& work, size_t b) {
  const VcmBudget& budget = kVcmBudgets[b];
  const size_t pixels = pixel_moments.size() / kPixelMoments;
  const auto moment_of = [&](size_t p, size_t c) {
    return pixel_moments[p * kPixelMoments + b * kCameraSampleChoices + c];
  };
  // Each pixel's steps along the lower convex hull of its (n, M(n)): from one camera sample to
  // the count that lowers the moment most per added sample, and on. A step's rate is what a camera
  // sample must cost, in moment, for the step to pay.
  struct Step {
    double rate;
    std::uint32_t pixel;
    std::uint8_t to;  // index into kCameraSampleCounts
  };
  std::vector<Step> steps;
  double moment = 0.0, samples = double(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    moment += moment_of(p, 0);
    for (size_t from = 0; from + 1 < kCameraSampleChoices;) {
      size_t to = from;
      double best_rate = 0.0;
      for (size_t c = from + 1; c < kCameraSampleChoices; ++c) {
        const double rate =
            (moment_of(p, from) - moment_of(p, c)) / (kCameraSampleCounts[c] - kCameraSampleCounts[from]);
        if (rate > best_rate) best_rate = rate, to = c;  // NaN and inf - inf never step
      }
      if (to == from) break;
      steps.push_back({best_rate, std::uint32_t(p), std::uint8_t(to)});
      from = to;
    }
  }
  // Lowering the price of a camera sample takes the steps in order of their rates, each pixel's in
  // its own order (its rates fall); along the way, the least product.
  std::stable_sort(steps.begin(), steps.end(), [](const Step& x, const Step& y) { return x.rate > y.rate; });
  const auto cost_of = [&](double total) {
    return iteration_cost(work, budget, pixels > 0 ? total / double(pixels) : 1.0);
  };
  BudgetPlan best{{}, moment, cost_of(samples)};
  size_t best_steps = 0;
  std::vector<std::uint8_t> choice(pixels, 0);
  for (size_t k = 0; k < steps.size() && std::isfinite(moment); ++k) {
    const Step& step = steps[k];
    std::uint8_t& c = choice[step.pixel];
    moment += moment_of(step.pixel, step.to) - moment_of(step.pixel, c);
    samples += kCameraSampleCounts[step.to] - kCameraSampleCounts[c];
    c = step.to;
    const double cost = cost_of(samples);
    if (moment * cost < best.product()) best.moment = moment, best.cost = cost, best_steps = k + 1;
  }
  // The plan, its moment summed afresh (the running sum has the rounding of every step).
  std::fill(choice.begin(), choice.end(), std::uint8_t(0));
  for (size_t k = 0; k < best_steps; ++k) choice[steps[k].pixel] = steps[k].to;
  best.camera_samples.resize(pixels);
  best.moment = 0.0;
  for (size_t p = 0; p < pixels; ++p) {
    best.camera_samples[p] = std::uint8_t(kCameraSampleCounts[choice[p]]);
    best.moment += moment_of(p, choice[p]);
  }
  return best;
}

VcmChoice choose_budget(std::span<const double> pixel_moments, const VcmWork& work, int max_light_paths) {
  VcmChoice out;
  out.measured = true;
  out.work = work;
  double best_product = std::numeric_limits<double>::infinity();
  for (size_t b = 0; b < kVcmBudgetCount; ++b) {
    BudgetPlan plan = plan_budget(pixel_moments, work, b);
    if (kVcmBudgets[b].light_paths <= max_light_paths && plan.product() < best_product) {
      best_product = plan.product();
      out.budget = kVcmBudgets[b];
      out.camera_samples = std::move(plan.camera_samples);
    }
    plan.camera_samples = {};
    out.plans[b] = std::move(plan);
  }
  return out;  // kEveryTechnique, one camera sample a pixel, should no product be finite
}

}  // namespace rt
