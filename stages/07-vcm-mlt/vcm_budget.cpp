#include "07-vcm-mlt/vcm_budget.h"

#include <cmath>
#include <limits>

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

double iteration_cost(const VcmWork& work, const VcmBudget& b) {
  const double camera = double(work.camera_vertices), light_points = double(work.light_points);
  if (b.light_paths == 0) return kCostPathTracerVertex * (camera + light_points);
  const double per_light_path = double(b.light_paths);
  double cost =
      kCostCameraVertex * camera + kCostLightPoint * light_points +
      per_light_path * (kCostLightSubpath * double(work.light_subpaths) +
                        kCostLightVertex * double(work.light_vertices) + kCostCameraLink * double(work.camera_links));
  if (b.connect) cost += kCostConnection * double(work.connections);
  if (b.merge != Merging::none) {
    const MergeWork& m = b.connect ? work.with_connections : work.without_connections;
    cost += per_light_path * (kCostMerge * double(m.merges) + kCostPhoton * double(m.photons));
  }
  return cost;
}

void add_budget_moments(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& first, Color value,
                        std::span<double> sums) {
  const double squared = double(glm::dot(value, value));
  if (!(squared > 0.0) || !std::isfinite(squared)) return;  // the image drops such a sample too
  const TechniqueDensities taken = technique_densities(path, made_by, techniques_on_path(path, made_by, first));
  if (!(taken.sum > 0.0) || !(taken.own > 0.0)) return;
  // (f / q_1)^2 q_1 / q_b, each density relative to the same connection's: f = value n p.
  const double balance_squared = squared * taken.own * taken.own / taken.sum;
  for (size_t b = 0; b < kVcmBudgetCount; ++b) {
    const VcmTechniques on = techniques_on_path(path, made_by, techniques_within(first, kVcmBudgets[b]));
    const double q_b = technique_densities(path, made_by, on).sum;
    sums[b] += q_b > 0.0 ? balance_squared / q_b : std::numeric_limits<double>::infinity();
  }
}

VcmBudget cheapest_budget(std::span<const double> moments, const VcmWork& work, int max_light_paths) {
  VcmBudget best = kEveryTechnique;  // should no estimate be finite
  double best_product = std::numeric_limits<double>::infinity();
  for (size_t b = 0; b < kVcmBudgetCount; ++b) {
    if (kVcmBudgets[b].light_paths > max_light_paths) continue;
    const double product = moments[b] * iteration_cost(work, kVcmBudgets[b]);
    if (product < best_product) best = kVcmBudgets[b], best_product = product;
  }
  return best;
}

}  // namespace rt
