// Stage 7: the multiple importance weights of vertex connection and merging (Georgiev, Křivánek,
// Davidovič & Slusallek, "Light Transport Simulation with Vertex Connection and Merging", SIGGRAPH
// Asia 2012). A path x_0 ... x_k (x_0 the pinhole, x_k on a light) can be made by
//   - a connection (t): the camera subpath samples x_0 ... x_t-1, the light subpath x_k ... x_t,
//     and a shadow ray joins x_t-1 to x_t (stage 6's strategy (s, t), s = k + 1 - t), with
//         p_t = prod_(j < t) pc_j  prod_(j >= t) pl_j,
//     pc_j the density of x_j sampled from the camera side (from x_j-1), pl_j from the light side
//     (from x_j+1, or the light's own choice of x_k);
//   - a merge at x_i: both subpaths reach x_i, the light subpath's vertex near the camera subpath's
//     within the radius r, which happens with probability ~ pc_i pi r^2 once the light's vertex is
//     there; one camera subpath merges with all N light subpaths of the iteration, so
//         p_merge,i = N pi r^2 pc_i prod_(j < i) pc_j prod_(j >= i) pl_j = eta pl_i p_i+1,
//     eta = N pi r^2 (photon mapping recast as a path sampler: the paper's section 4).
// All of them are weighed by the power heuristic, w = p^2 / sum over the techniques of p^2: one
// estimator in which a merge takes over where every connection is improbable (a caustic seen in a
// mirror) and a connection where a merge is blurry and noisy (diffuse light).
#pragma once

#include <span>

namespace rt {

// One vertex of a full path, in camera-to-light order: its densities per unit area from either
// end and whether it scatters by a delta lobe (no connection or merge can end there).
struct PathDensity {
  float camera, light;  // pc, pl
  bool delta;
};

// The techniques a render uses; each --mode of stage7 is one set of them.
struct VcmTechniques {
  bool hit_light = true;    // the camera subpath reaches the light (t = k + 1)
  bool light_trace = true;  // a light vertex seen by the pinhole (t = 1), splatted
  bool next_event = true;   // a fresh point on a light joined to x_t-1 (t = k, s = 1)
  bool connect = true;      // the connections to the light subpath's vertices (2 <= t <= k - 1)
  bool merge = true;        // merges at x_1 ... x_k-1
  // Light subpaths per pixel and iteration: the light-tracing technique's number of samples (each
  // pixel's camera subpath connects to one light subpath, and merges with all of them).
  float light_paths = 1.0f;
  float eta = 0.0f;  // N pi r^2: light subpaths per iteration times the merge disk's area
};

// Which technique made the path: a connection with `t` camera vertices, or a merge at x_t-1 (the
// camera subpath's last vertex, where t vertices of it were sampled).
struct Technique {
  enum Kind { connection, merge } kind;
  int t;
};

// Task stage7.vcm.weight. The densities of every technique of `on` that can make the path whose
// vertices' densities are `path` (x_0 ... x_k, k >= 1), each times its number of samples per pixel
// (n p: the light-tracing technique has light_paths, a merge's eta is in its density), relative to
// the connection that made it or shares its t: a connection t needs 1 <= t <= k + 1 and neither
// x_t-1 nor x_t (where t <= k) delta; a merge at x_i needs 1 <= i <= k - 1 and x_i not delta.
// `own` is `made_by`'s, 0 if it is not one of them. A density of 0 (a direction a BSDF cannot
// sample) stands for 1, as in stage 6's strategy_weight.
struct TechniqueDensities {
  double own = 0.0;             // n p of made_by
  double sum = 0.0;             // sum over the techniques of n p: the balance heuristic's denominator
  double sum_of_squares = 0.0;  // sum of (n p)^2: the power heuristic's
};
TechniqueDensities technique_densities(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& on);

// The power heuristic weight of `made_by`, own^2 / sum_of_squares (0 where no technique makes the
// path). With merging off it is stage 6's strategy_weight of the same path (a test checks it).
float vcm_weight(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& on);

}  // namespace rt
