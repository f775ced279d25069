// Stage 6: bidirectional path tracing (Veach & Guibas, "Bidirectional Estimators for Light
// Transport", EGWR 1994; Lafortune & Willems, "Bi-directional Path Tracing", Compugraphics 1993;
// Veach's thesis, chapter 10). Each sample traces a camera subpath z_0 ... z_nc-1 (z_0 the pinhole)
// and a light subpath y_0 ... y_nl-1 (y_0 on an emitter), then joins every prefix pair: strategy
// (s, t) takes s light vertices and t camera vertices and connects y_s-1 to z_t-1 by a shadow ray,
// a full path of s + t vertices (s + t - 1 edges). The special cases:
//   s = 0: the camera subpath itself hit an emitter (a path tracer's estimate without NEE);
//   s = 1: a fresh point on a light, sampled for z_t-1 (a path tracer's next-event estimation);
//   t = 1: y_s-1 seen by the camera directly: a light tracer's estimate, splatted to the pixel
//          where it lands, not the pixel the sample belongs to;
//   t = 0 (a light path that reaches the pinhole) is impossible: a pinhole has no area.
// Every strategy alone is an unbiased estimator of the paths of its length; they are combined by
// the power heuristic over all strategies that could have produced the same path (MIS; Veach &
// Guibas 1995), which needs each vertex's density in both directions (path_vertex.h).
#pragma once

#include "06-light-transport/light_emission.h"
#include "06-light-transport/path_vertex.h"

#include <span>

namespace rt {

// A vertex's two area densities and whether it scattered by a delta lobe: all the MIS weight reads.
// No default values: mis_weight keeps two arrays of kMaxSubpathVertices of them on the stack for
// every connection and fills only the s + t it uses.
struct VertexDensity {
  float fwd, rev;
  bool delta;
};

// Task stage6.bdpt.mis_weight. The power heuristic weight of strategy (s, t) for its path, from the
// densities of its t camera vertices z_0 ... z_t-1 and s light vertices y_0 ... y_s-1, each with
// its pdf_rev already that of the full path (mis_weight below sets the ones at the connection):
//     w_(s,t) = p_s^2 / sum_i p_i^2 = 1 / (1 + sum_(i != s) (p_i / p_s)^2),
// the ratios built one vertex at a time: moving z_i to the light side multiplies the path's
// density by z_i.rev / z_i.fwd, moving y_i to the camera side by y_i.rev / y_i.fwd. A strategy
// whose connection would touch a delta vertex does not exist (its density is 0), nor does t = 0
// (the pinhole). A density of 0 (a direction a BSDF cannot sample) stands for 1 in the ratios,
// as for PBR 3rd ed. section 16.3.4's remap0: such a strategy's own density is 0 where it matters.
float strategy_weight(std::span<const VertexDensity> camera, std::span<const VertexDensity> light);

// The weight of strategy (s, t) on the real subpaths: their densities, with those of the (up to)
// four vertices around the connection recomputed for the joined path. `sampled_light` is the light
// point strategy s = 1 sampled (it replaces y_0).
float mis_weight(const LightingScene& scene, const Camera& camera, std::span<const PathVertex> camera_path,
                 std::span<const PathVertex> light_path, int s, int t, const PathVertex* sampled_light);

// What one strategy found: the path's unweighted contribution f / p, and for t = 1 the film point
// it lands on.
struct StrategySample {
  Color value{0.0f};
  std::optional<Vec2> film_point;
};

// Task stage6.bdpt.connect. The contribution of strategy (s, t), unweighted, for s + t >= 2, t >= 1:
//   s = 0:  beta(z_t-1) Le(z_t-1 -> z_t-2);
//   t = 1:  beta(y) f(y) |cos_y| We(w) cos_cam / d^2, y = y_s-1 seen from the pinhole along w;
//   s = 1:  beta(z) f(z) G(z, y) Le(y -> z) / (P_choice p_A), y a fresh light point (`light_point`);
//   else:   beta(z) f(z) G(z, y) f(y) beta(y);
// f the vertices' `scattering`, every connection behind a shadow ray. Zero where a connection
// touches a delta vertex.
StrategySample connect_strategy(const LightingScene& scene, const Camera& camera,
                                std::span<const PathVertex> camera_path, std::span<const PathVertex> light_path,
                                int s, int t, const PathVertex* light_point, const OffsetPolicy& offset);

// A light vertex for strategy s = 1: a uniform point on an emitter chosen by power.
std::optional<PathVertex> sample_light_vertex(const LightingScene& scene, float u_choice, Vec2 u);

// One strategy alone, for teaching (stage6 --strategy s,t): every other is skipped, and it is not
// weighted, so its image is that strategy's own unbiased estimate of the paths of length s + t - 1.
struct StrategyFilter {
  int s = -1, t = -1;  // -1, -1: all strategies, weighted
  bool all() const { return s < 0; }
};

struct BdptOptions {
  WalkSettings walk;
  StrategyFilter only;
};

// A film contribution of the t = 1 strategies: where it lands and what it adds.
struct Splat {
  Vec2 film_point;
  Color value;
};

// One BDPT sample for the camera ray through a pixel: returns what the strategies with t >= 2 add
// to that pixel and appends the t = 1 contributions to `splats`. `camera_path` and `light_path` are
// scratch space, reused between samples.
template <SamplerType S>
Color bdpt_sample(const LightingScene& scene, const Camera& camera, const Ray& camera_ray, const BdptOptions& options,
                  S& sampler, std::vector<PathVertex>& camera_path, std::vector<PathVertex>& light_path,
                  std::vector<Splat>& splats);

}  // namespace rt
