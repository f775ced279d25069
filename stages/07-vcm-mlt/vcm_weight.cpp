#include "07-vcm-mlt/vcm_weight.h"

#include "common/task.h"

namespace rt {

TechniqueDensities technique_densities(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& on) {
  const int k = int(path.size()) - 1;  // the path's last vertex, on the light
  const int t_made = made_by.t;
  if (k < 1 || t_made < 1 || t_made > k + 1) return {};
  // BEGIN TASK stage7.vcm.weight
  const auto remap = [](float pdf) { return double(pdf != 0.0f ? pdf : 1.0f); };
  // Each connection's number of samples: the light-tracing technique has one per light subpath.
  const auto count = [&](int t) { return t == 1 ? double(on.light_paths) : 1.0; };
  const auto connection_exists = [&](int t) {
    if (t == k + 1) return on.hit_light && !path[size_t(k)].delta;
    if (!(t == 1 ? on.light_trace : t == k ? on.next_event : on.connect)) return false;
    return !path[size_t(t - 1)].delta && !path[size_t(t)].delta;
  };
  const auto merge_exists = [&](int i) { return on.merge && i >= 1 && i <= k - 1 && !path[size_t(i)].delta; };
  // Every density relative to p_t of the connection with t_made camera vertices, built one vertex
  // at a time: p_t+1 / p_t = pc_t / pl_t. A merge at x_t-1 is eta pl_t-1 p_t.
  TechniqueDensities out;
  const auto add = [&](int t, double ratio) {
    if (connection_exists(t)) {
      const double c = count(t) * ratio;
      out.sum += c;
      out.sum_of_squares += c * c;
    }
    if (merge_exists(t - 1)) {
      const double m = double(on.eta) * remap(path[size_t(t - 1)].light) * ratio;
      out.sum += m;
      out.sum_of_squares += m * m;
    }
  };
  add(t_made, 1.0);
  double ratio = 1.0;
  for (int t = t_made + 1; t <= k + 1; ++t) {
    ratio *= remap(path[size_t(t - 1)].camera) / remap(path[size_t(t - 1)].light);
    add(t, ratio);
  }
  ratio = 1.0;
  for (int t = t_made - 1; t >= 1; --t) {
    ratio *= remap(path[size_t(t)].light) / remap(path[size_t(t)].camera);
    add(t, ratio);
  }
  const bool merge = made_by.kind == Technique::merge;
  if (merge ? merge_exists(t_made - 1) : connection_exists(t_made))
    out.own = merge ? double(on.eta) * remap(path[size_t(t_made - 1)].light) : count(t_made);
  return out;
  // PLACEHOLDER
  // report_unfinished_task("stage7.vcm.weight");
  // (void)on;
  // // Connections alike, no merges.
  // return {.own = made_by.kind == Technique::connection ? 1.0 : 0.0, .sum = k + 1.0, .sum_of_squares = k + 1.0};
  // END TASK
}

float vcm_weight(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& on) {
  const TechniqueDensities d = technique_densities(path, made_by, on);
  return d.sum_of_squares > 0.0 ? float(d.own * d.own / d.sum_of_squares) : 0.0f;
}

}  // namespace rt
