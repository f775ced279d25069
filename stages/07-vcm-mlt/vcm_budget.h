// Stage 7: how much of each technique an iteration of vertex connection and merging runs, chosen
// for the scene. Every technique that VCM adds costs time on every path, also where it adds little:
// on the Cornell box an iteration's light subpaths, connections and merges make it six times as
// slow as a path tracer's sample for no less noise, and on a caustic seen on a diffuse floor one
// light subpath per pixel is too few. So, after the idea of Grittmann, Yazici, Georgiev &
// Slusallek ("Efficiency-Aware Multiple Importance Sampling for Bidirectional Rendering
// Algorithms", SIGGRAPH 2022), the first iteration runs every technique and estimates, for each of
// a few budgets, what an iteration of it would cost and how noisy it would be, with each pixel's
// camera samples per iteration chosen for it (as Grittmann et al. choose them), and the remaining
// iterations run the budget with the least error for their time.
//
// Noise. With the balance heuristic an iteration's pixel estimate combines the techniques t, each
// taken n_t times with density p_t, as one sample from their mixture q = sum_t n_t p_t; its second
// moment is the integral of f^2 / q. The first iteration's samples come from the mixture q_1 of
// every technique, so for a budget b with mixture q_b
//     M_b = integral f^2 / q_b = E_1[(f / q_1)^2 q_1 / q_b],
// each sample's balance-weighted contribution squared times q_1 / q_b, summed per pixel. The
// render weighs by the power heuristic; both heuristics are close to the best combination (Veach's
// thesis, chapter 9), and only the budgets' order matters here.
//
// Merges. A merge's path is a connection's with one vertex moved by up to r, and its densities are
// those of the light vertex's place: on a diffuse path in a corner that approximation makes q_1 / q_b
// of a budget without merges 10^8 or more, and one such sample outweighs the whole image's other
// terms (measured on the Cornell box). So merges are counted only on the paths that no connection
// can make (the light hit aside: specular, diffuse, specular chains), and a chosen budget merges
// only there too. Elsewhere a merge's blur would be bias that no second moment sees: on the caustic
// seen on the floor, merging at one pixel footprint made the error at equal time 5 times light
// tracing's (docs/stage7.md, section 5).
//
// Cost. Counted, never timed, so that the choice and the image are the same in every run: the
// rays each part of the first iteration traced and the merges it made, each weighed by a measured
// cost per unit (vcm_budget.cpp).
#pragma once

#include "07-vcm-mlt/vcm_weight.h"

#include "common/math.h"

#include <array>
#include <cstdint>
#include <iterator>
#include <span>
#include <string>
#include <vector>

namespace rt {

// Where camera vertices merge with the light vertices near them.
enum class Merging {
  none,
  where_needed,  // on the paths no connection can make, the light hit aside (see above)
  everywhere,    // as Georgiev et al. publish VCM
};

// An iteration's budget: light subpaths per pixel (0: none, so no light tracing, connections or
// merges: the camera subpaths alone, path tracing with next-event estimation), whether camera
// vertices connect to their pixel's light subpath, and where they merge with all of them.
struct VcmBudget {
  int light_paths = 1;
  bool connect = true;
  Merging merge = Merging::everywhere;
  bool operator==(const VcmBudget&) const = default;
};

// The budgets the first iteration chooses from: none, one or eight light subpaths per pixel (eight
// is about what photon mapping behind glass and a caustic on a floor ask for: docs/stage7.md,
// section 5), each with or without connections and merges where needed.
inline constexpr VcmBudget kVcmBudgets[] = {
    {0, false, Merging::none},         {1, false, Merging::none},        {1, false, Merging::where_needed},
    {1, true, Merging::none},          {1, true, Merging::where_needed}, {8, false, Merging::none},
    {8, false, Merging::where_needed}, {8, true, Merging::none},         {8, true, Merging::where_needed}};
inline constexpr size_t kVcmBudgetCount = std::size(kVcmBudgets);
// The first iteration's: one light subpath per pixel and every technique everywhere (and every
// iteration's with --budget all).
inline constexpr VcmBudget kEveryTechnique = {1, true, Merging::everywhere};

// "no light subpaths (path tracing)", "8 light subpaths a pixel, connections, merges where only they
// reach", for the program's report.
std::string describe(const VcmBudget& b);
// The program's words for a budget: "all" (kEveryTechnique), "pt" (no light subpaths), and for
// each other of kVcmBudgets its light subpaths a pixel, "c" for connections, "m" for merges: "1",
// "8cm", ...
std::string budget_word(const VcmBudget& b);

// The techniques of `all` that budget b runs, `all` being those of one light subpath per pixel
// (light_paths 1, its eta): b's light subpaths multiply the light-tracing samples and eta.
VcmTechniques techniques_within(VcmTechniques all, const VcmBudget& b);

// Where a chosen budget merges (see above): on a path that some connection of `on` other than the
// light hit can make, `on` without its merges; elsewhere `on`.
VcmTechniques techniques_on_path(std::span<const PathDensity> path, Technique made_by, VcmTechniques on);

// The merging a chosen budget would do in the first iteration, which has one light subpath per
// pixel. A merge is needed only where the connection joining the merged vertex to its predecessor
// on either subpath is off or cannot end there (a mirror or glass), so a budget with connections
// merges at fewer vertices and keeps fewer photons than one without.
struct MergeWork {
  std::uint64_t photons = 0;  // light vertices it would put in the grid
  std::uint64_t merges = 0;   // of those, the ones found within r of a camera vertex where it merges
};

// What the first iteration did, counted over the whole image (it runs one light subpath per pixel).
struct VcmWork {
  std::uint64_t camera_vertices = 0;  // rays the camera subpaths traced
  std::uint64_t light_points = 0;     // next-event estimation's shadow rays
  std::uint64_t light_subpaths = 0;   // their starts: a light and a point on it chosen
  std::uint64_t light_vertices = 0;   // rays the light subpaths traced
  std::uint64_t camera_links = 0;     // light-tracing's shadow rays to the pinhole
  std::uint64_t connections = 0;      // shadow rays between camera and light subpath vertices
  MergeWork with_connections;         // a chosen budget's merging, with connections
  MergeWork without_connections;      // and without
};

// Each pixel's camera samples per iteration: a budget with light subpaths gives every pixel one of
// these, chosen for it. One camera sample a pixel wastes a budget of eight light subpaths a pixel
// where only the camera reaches the light (a lamp seen in a glass ball: the caustic scene's worst
// pixels), and eight waste it where the light subpaths do the work. Grittmann et al. choose the
// camera samples per pixel for this reason; the light subpaths stay one set for the whole image.
inline constexpr int kCameraSampleCounts[] = {1, 2, 4, 8};
inline constexpr size_t kCameraSampleChoices = std::size(kCameraSampleCounts);
// A pixel's second moments, one per budget of kVcmBudgets and camera sample count: index
// b kCameraSampleChoices + c.
inline constexpr size_t kPixelMoments = kVcmBudgetCount * kCameraSampleChoices;

// The cost of an iteration with budget b whose pixels take `camera_samples` camera samples each on
// average, in camera vertices' time: each count times its cost per unit, the camera side's times
// the camera samples, the light side's times b's light subpaths per pixel, and the merges' times
// both (each camera sample merges with every light subpath).
double iteration_cost(const VcmWork& work, const VcmBudget& b, double camera_samples = 1.0);

// One sample of the first iteration, the terms it adds to each budget's second moment (see above).
// The light-tracing samples that land in a pixel are the budget's N_L / P light subpaths a pixel,
// its other techniques' samples n, the pixel's camera samples: so, relative to the first
// iteration's mixture, q_b,n = n camera[b] + light[b], and the term is balance_squared / q_b,n.
struct BudgetTerms {
  double balance_squared = 0.0;  // (f / q_1)^2 q_1
  std::array<double, kVcmBudgetCount> camera{}, light{};
};
// `value` is the unweighted contribution f / (n p) of technique `made_by`, `path` its densities and
// `first` the techniques the first iteration had for it (every one the mode allows, one light
// subpath per pixel). A sample the image drops (not finite, or 0) has no terms.
BudgetTerms budget_terms(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& first, Color value);
// Adds a sample's terms to a pixel's second moments (kPixelMoments). A budget none of whose
// techniques can make a path that carries light would leave that light out of the image: its sum
// becomes infinite.
void add_budget_moments(const BudgetTerms& terms, std::span<double> sums);

// A budget's plan: each pixel's camera samples per iteration (kCameraSampleCounts), and what the
// first iteration estimates an iteration of it would leave as second moment (summed over the
// image) and cost.
struct BudgetPlan {
  std::vector<std::uint8_t> camera_samples;
  double moment = 0.0, cost = 0.0;
  double product() const { return moment * cost; }  // what error^2 x time would be
};
// The camera samples per pixel that make budget b's moment times cost least, given each pixel's
// moments (`pixel_moments`, kPixelMoments a pixel). For n_p the moment is sum_p M_p(n_p) and the
// cost C_light + C_camera mean_p(n_p). The plan is the best of the allocations that minimise
// moment + mu (camera samples) for some price mu of a camera sample: lowering mu from infinity
// adds samples one pixel at a time, each pixel along the lower convex hull of its (n, M_p(n)), in
// order of how much moment a sample saves. Where the M_p are convex in n, as a / n + c is, the
// least product lies on that path.
BudgetPlan plan_budget(std::span<const double> pixel_moments, const VcmWork& work, size_t b);

// What the first iteration measured and chose, for the program's report and the tests.
struct VcmChoice {
  VcmBudget budget = kEveryTechnique;  // what the iterations after the first ran
  bool measured = false;               // false: no choice was made (--budget all, another mode, 1 iteration)
  std::array<BudgetPlan, kVcmBudgetCount> plans{};  // per budget of kVcmBudgets, without its camera samples
  std::vector<std::uint8_t> camera_samples;         // the chosen budget's per pixel; empty: one each
  VcmWork work;                                     // what the first iteration counted (iteration_cost)
};

// The plan (camera samples per pixel included) of each budget, and the budget whose iterations reach
// a given error soonest: the least second moment times cost. Budgets of more than `max_light_paths`
// light subpaths per pixel are left out; kEveryTechnique if no product is finite.
VcmChoice choose_budget(std::span<const double> pixel_moments, const VcmWork& work, int max_light_paths);

}  // namespace rt
