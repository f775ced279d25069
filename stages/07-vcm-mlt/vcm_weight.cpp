#include "07-vcm-mlt/vcm_weight.h"

#include "common/task.h"

namespace rt {

float vcm_weight(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& on) {
  const int k = int(path.size()) - 1;  // the path's last vertex, on the light
  const int t_made = made_by.t;
  if (k < 1 || t_made < 1 || t_made > k + 1) return 0.0f;
  // BEGIN TASK stage7.vcm.weight
  const auto remap = [](float pdf) { return double(pdf != 0.0f ? pdf : 1.0f); };
  const auto connection_exists = [&](int t) {
    if (t == k + 1) return on.hit_light && !path[size_t(k)].delta;
    if (!(t == 1 ? on.light_trace : on.connect)) return false;
    return !path[size_t(t - 1)].delta && !path[size_t(t)].delta;
  };
  const auto merge_exists = [&](int i) { return on.merge && i >= 1 && i <= k - 1 && !path[size_t(i)].delta; };
  // Every density relative to p_t of the connection with t_made camera vertices, built one vertex
  // at a time: p_t+1 / p_t = pc_t / pl_t. A merge at x_t-1 is eta pl_t-1 p_t.
  double sum = 0.0;
  const auto add = [&](int t, double ratio) {
    if (connection_exists(t)) sum += ratio * ratio;
    if (merge_exists(t - 1)) {
      const double m = double(on.eta) * remap(path[size_t(t - 1)].light) * ratio;
      sum += m * m;
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
  if (merge ? !merge_exists(t_made - 1) : !connection_exists(t_made)) return 0.0f;
  const double own = merge ? double(on.eta) * remap(path[size_t(t_made - 1)].light) : 1.0;
  return sum > 0.0 ? float(own * own / sum) : 0.0f;
  // PLACEHOLDER
  // report_unfinished_task("stage7.vcm.weight");
  // (void)on;
  // return made_by.kind == Technique::connection ? 1.0f / float(k + 1) : 0.0f;  // connections alike, no merges
  // END TASK
}

}  // namespace rt
