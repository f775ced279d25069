// Stage 7's budgets (vcm_budget.h): what each keeps of the mode's techniques, what its iterations
// cost, which one the first iteration picks, where a chosen budget keeps its merges, and the
// second moments the first iteration estimates, on paths whose answer is written out by hand.
#include "07-vcm-mlt/vcm_budget.h"
#include "07-vcm-mlt/vcm.h"

#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <limits>

namespace rt {
namespace {

size_t index_of(const VcmBudget& b) {
  for (size_t i = 0; i < kVcmBudgetCount; ++i)
    if (kVcmBudgets[i] == b) return i;
  ADD_FAILURE() << "no budget " << describe(b);
  return 0;
}

TEST(VcmBudget, EachBudgetKeepsWhatTheModeAllowsOfItsTechniques) {
  VcmTechniques vcm = techniques_of(VcmMode::vcm);
  vcm.eta = 2.0f;
  const VcmTechniques none = techniques_within(vcm, {0, true, Merging::where_needed});
  EXPECT_TRUE(none.hit_light && none.next_event);  // the path tracer's two
  EXPECT_FALSE(none.light_trace || none.connect || none.merge);
  EXPECT_EQ(none.light_paths, 0.0f);
  const VcmTechniques eight = techniques_within(vcm, {8, false, Merging::where_needed});
  EXPECT_TRUE(eight.light_trace && eight.merge && eight.next_event);
  EXPECT_FALSE(eight.connect);
  EXPECT_EQ(eight.light_paths, 8.0f);
  EXPECT_EQ(eight.eta, 16.0f);  // N pi r^2 with eight times the light subpaths
  // A budget never turns on what the mode has off.
  const VcmTechniques ppm = techniques_within(techniques_of(VcmMode::ppm), {8, true, Merging::where_needed});
  EXPECT_FALSE(ppm.connect || ppm.light_trace || ppm.next_event);
  EXPECT_TRUE(ppm.merge && ppm.hit_light);
}

// A first iteration's counts, made up.
constexpr VcmWork kWork{.camera_vertices = 1000,
                        .light_points = 800,
                        .light_subpaths = 900,
                        .light_vertices = 3000,
                        .camera_links = 3000,
                        .connections = 2000,
                        .with_connections = {.photons = 1000, .merges = 5000},
                        .without_connections = {.photons = 2500, .merges = 9000}};

TEST(VcmBudget, AnIterationCostsWhatItsBudgetRuns) {
  const VcmWork& work = kWork;
  const auto cost = [&](VcmBudget b) { return iteration_cost(work, b); };
  EXPECT_LT(cost({0, false, Merging::none}), cost({1, false, Merging::none}));
  EXPECT_LT(cost({1, false, Merging::none}), cost({1, true, Merging::none}));
  EXPECT_LT(cost({1, true, Merging::none}), cost({1, true, Merging::where_needed}));
  EXPECT_LT(cost({1, true, Merging::where_needed}), cost({8, true, Merging::where_needed}));
  // The light side and the merges scale with the light subpaths; the camera side and the
  // connections (each camera vertex to its own pixel's one subpath) do not.
  EXPECT_NEAR(cost({8, false, Merging::where_needed}) - cost({8, false, Merging::none}),
              8.0 * (cost({1, false, Merging::where_needed}) - cost({1, false, Merging::none})),
              1e-9 * cost({8, false, Merging::where_needed}));
  EXPECT_NEAR(cost({8, true, Merging::none}) - cost({8, false, Merging::none}),
              cost({1, true, Merging::none}) - cost({1, false, Merging::none}), 1e-9 * cost({8, true, Merging::none}));
  // A budget with connections merges at fewer vertices, one without at more: each pays for its own.
  VcmWork unconnected_free = work;
  unconnected_free.without_connections = {};
  EXPECT_EQ(iteration_cost(unconnected_free, {8, true, Merging::where_needed}), cost({8, true, Merging::where_needed}));
  EXPECT_EQ(iteration_cost(unconnected_free, {8, false, Merging::where_needed}), cost({8, false, Merging::none}));
  // Without light subpaths, nothing on the light side counts.
  VcmWork lighter = work;
  lighter.light_subpaths = lighter.light_vertices = lighter.camera_links = lighter.connections = 0;
  lighter.with_connections = lighter.without_connections = {};
  EXPECT_EQ(iteration_cost(lighter, {0, false, Merging::none}), cost({0, false, Merging::none}));
  // Camera samples a pixel: the camera side and the merges scale with them, the light side does not.
  for (const VcmBudget& b : kVcmBudgets) {
    const double per_sample = iteration_cost(work, b, 1.0) - iteration_cost(work, b, 0.0);
    EXPECT_GT(per_sample, 0.0) << describe(b);
    EXPECT_NEAR(iteration_cost(work, b, 4.0), iteration_cost(work, b, 0.0) + 4.0 * per_sample, 1e-9 * cost(b))
        << describe(b);
  }
  EXPECT_EQ(iteration_cost(work, {0, false, Merging::none}, 0.0), 0.0);
  EXPECT_NEAR(iteration_cost(work, {8, true, Merging::where_needed}, 0.0),
              8.0 * iteration_cost(work, {1, true, Merging::where_needed}, 0.0), 1e-9 * cost({8, true, Merging::none}));
  const auto merges_per_sample = [&](int light_paths) {
    const auto at = [&](Merging m, double n) { return iteration_cost(work, {light_paths, true, m}, n); };
    return at(Merging::where_needed, 2.0) - at(Merging::where_needed, 1.0) - at(Merging::none, 2.0) +
           at(Merging::none, 1.0);
  };
  EXPECT_GT(merges_per_sample(1), 0.0);
  EXPECT_NEAR(merges_per_sample(8), 8.0 * merges_per_sample(1), 1e-9 * cost({8, true, Merging::none}));
}

TEST(VcmBudget, EachBudgetHasItsOwnWord) {
  // The words of --budget: every budget's is different and names it.
  std::set<std::string> words{budget_word(kEveryTechnique)};
  for (const VcmBudget& b : kVcmBudgets) words.insert(budget_word(b));
  EXPECT_EQ(words.size(), kVcmBudgetCount + 1);
  EXPECT_EQ(budget_word(kEveryTechnique), "all");
  EXPECT_EQ(budget_word({0, false, Merging::none}), "pt");
  EXPECT_EQ(budget_word({8, true, Merging::where_needed}), "8cm");
  EXPECT_EQ(budget_word({1, false, Merging::none}), "1");
}

// Pixel moments for `pixels` pixels, every budget's and camera sample count's `value`.
std::vector<double> pixel_moments(size_t pixels, double value) {
  return std::vector<double>(pixels * kPixelMoments, value);
}
double& moment_at(std::vector<double>& m, size_t pixel, size_t b, size_t c) {
  return m[pixel * kPixelMoments + b * kCameraSampleChoices + c];
}

TEST(VcmBudget, TheChoiceIsTheLeastSecondMomentTimesCost) {
  const VcmWork& work = kWork;
  const double infinite = std::numeric_limits<double>::infinity();
  // One pixel, each moment the inverse of its cost, so that all products tie at 1 for every number
  // of camera samples, but one budget's a little lower.
  std::vector<double> moments = pixel_moments(1, 0.0);
  const auto set = [&](size_t b, double scale) {
    for (size_t c = 0; c < kCameraSampleChoices; ++c)
      moment_at(moments, 0, b, c) = scale / iteration_cost(work, kVcmBudgets[b], kCameraSampleCounts[c]);
  };
  for (size_t b = 0; b < kVcmBudgetCount; ++b) set(b, 1.0);
  const size_t favoured = index_of({1, true, Merging::none});
  set(favoured, 0.99);
  const auto chosen = [&](int max_light_paths) {
    return testing::subject([&] {
      const VcmChoice c = choose_budget(moments, work, max_light_paths);
      return std::make_tuple(c.budget.light_paths, c.budget.connect, int(c.budget.merge), c.measured,
                             std::vector<int>(c.camera_samples.begin(), c.camera_samples.end()));
    });
  };
  const auto is = [](const auto& choice, const VcmBudget& b) {
    return std::get<0>(choice) == b.light_paths && std::get<1>(choice) == b.connect &&
           std::get<2>(choice) == int(b.merge);
  };
  EXPECT_TRUE(is(chosen(8), kVcmBudgets[favoured]));
  EXPECT_TRUE(std::get<3>(chosen(8)));
  EXPECT_EQ(std::get<4>(chosen(8)), std::vector<int>{1});  // a tie: one camera sample
  // A budget that would leave light out is never chosen, however cheap.
  set(favoured, infinite);
  set(index_of({0, false, Merging::none}), infinite);
  EXPECT_FALSE(is(chosen(8), {1, true, Merging::none}));
  EXPECT_FALSE(is(chosen(8), {0, false, Merging::none}));
  // Eight light subpaths a pixel are left out where the memory holds one.
  for (size_t b = 0; b < kVcmBudgetCount; ++b)
    set(b, kVcmBudgets[b].light_paths == 8 ? 1e-9 : kVcmBudgets[b].light_paths == 0 ? 2.0 : 1.0);
  EXPECT_EQ(std::get<0>(chosen(8)), 8);
  EXPECT_EQ(std::get<0>(chosen(1)), 1);
  // With no finite estimate at all, every technique, one camera sample a pixel.
  moments.assign(moments.size(), infinite);
  EXPECT_TRUE(is(chosen(1), kEveryTechnique));
  EXPECT_TRUE(std::get<4>(chosen(1)).empty());
}

TEST(VcmBudget, EachPixelTakesTheCameraSamplesThatMakeTheProductLeast) {
  // Five pixels whose moments fall as a_p / n + c_p with the camera samples n: a_p the part the
  // camera techniques carry, c_p the light-tracing part they leave. For a budget with light
  // subpaths and for the path tracer, the plan must match the best of all 4^5 choices, found by
  // trying each.
  const VcmWork& work = kWork;
  const double a[] = {0.0, 1.0, 30.0, 400.0, 2.0}, c[] = {5.0, 5.0, 1.0, 0.0, 0.0};
  constexpr size_t kPixels = std::size(a);
  std::vector<double> moments = pixel_moments(kPixels, 1.0);
  for (const VcmBudget& budget : {VcmBudget{8, true, Merging::where_needed}, VcmBudget{0, false, Merging::none}}) {
    const size_t b = index_of(budget);
    for (size_t p = 0; p < kPixels; ++p)
      for (size_t n = 0; n < kCameraSampleChoices; ++n)
        moment_at(moments, p, b, n) = a[p] / kCameraSampleCounts[n] + c[p];
    const auto [samples, moment, cost] = testing::subject([&] {
      const BudgetPlan plan = plan_budget(moments, work, b);
      return std::make_tuple(std::vector<int>(plan.camera_samples.begin(), plan.camera_samples.end()), plan.moment,
                             plan.cost);
    });
    ASSERT_EQ(samples.size(), kPixels);
    double best = std::numeric_limits<double>::infinity();
    std::vector<int> best_samples;
    for (size_t code = 0; code < 1024; ++code) {
      double m = 0.0, total = 0.0;
      std::vector<int> n(kPixels);
      for (size_t p = 0; p < kPixels; ++p) {
        n[p] = kCameraSampleCounts[(code >> (2 * p)) & 3];
        m += a[p] / n[p] + c[p];
        total += n[p];
      }
      const double product = m * iteration_cost(work, budget, total / kPixels);
      if (product < best) best = product, best_samples = n;
    }
    EXPECT_NEAR(moment * cost, best, 1e-9 * best) << describe(budget);
    EXPECT_EQ(samples, best_samples) << describe(budget);
    EXPECT_EQ(samples[0], 1) << describe(budget);  // nothing for camera samples to lower
    EXPECT_EQ(samples[3], 8) << describe(budget);  // the camera alone carries it
    // The plan's moment and cost are what its camera samples give.
    double m = 0.0, total = 0.0;
    for (size_t p = 0; p < kPixels; ++p) m += a[p] / samples[p] + c[p], total += samples[p];
    EXPECT_NEAR(moment, m, 1e-12 * m) << describe(budget);
    EXPECT_NEAR(cost, iteration_cost(work, budget, total / kPixels), 1e-9 * cost) << describe(budget);
  }
}

// The path x_0 (the pinhole) ... x_k, every vertex's densities 1 unless given, and which are delta.
std::vector<PathDensity> budget_path(std::initializer_list<bool> delta) {
  std::vector<PathDensity> out;
  for (const bool d : delta) out.push_back({1.0f, 1.0f, d});
  return out;
}

TEST(VcmWeight, AChosenBudgetMergesOnlyWhereNoConnectionReaches) {
  VcmTechniques on = techniques_of(VcmMode::vcm);
  on.eta = 0.5f;
  const std::vector<int> merges = testing::subject([&] {
    std::vector<int> out;
    // All diffuse: every connection makes it, so no merge does.
    const std::vector<PathDensity> diffuse = budget_path({false, false, false, false});
    out.push_back(techniques_on_path(diffuse, {Technique::merge, 2}, on).merge);
    // Pinhole, glass, floor, glass, light: only the light hit and merges at the floor.
    const std::vector<PathDensity> glass = budget_path({false, true, false, true, false});
    out.push_back(techniques_on_path(glass, {Technique::merge, 3}, on).merge);
    out.push_back(techniques_on_path(glass, {Technique::connection, 5}, on).merge);
    // Pinhole, glass, floor, wall, point light (delta): the floor connects to the wall ...
    const std::vector<PathDensity> wall = budget_path({false, true, false, false, true});
    out.push_back(techniques_on_path(wall, {Technique::merge, 3}, on).merge);
    // ... unless the budget has no connections (nothing else reaches the wall's light).
    VcmTechniques unconnected = on;
    unconnected.connect = false;
    out.push_back(techniques_on_path(wall, {Technique::merge, 3}, unconnected).merge);
    return out;
  });
  ASSERT_EQ(merges.size(), 5u);
  EXPECT_FALSE(merges[0]) << "a diffuse path";
  EXPECT_TRUE(merges[1]) << "glass, floor, glass: made by the merge";
  EXPECT_TRUE(merges[2]) << "glass, floor, glass: made by the light hit";
  EXPECT_FALSE(merges[3]) << "glass, floor, wall";
  EXPECT_TRUE(merges[4]) << "glass, floor, wall, without connections";
}

TEST(VcmWeight, BudgetMomentsAreTheBalanceHeuristicsSecondMoments) {
  // A diffuse path of three edges, densities made up, made by next-event estimation (t = 3):
  // merges leave (a connection makes it), and budget b's term is |v|^2 own^2 / (q_1 q_b), each q
  // the sum of n p over its connections, written out here: n the pixel's camera samples, light
  // tracing's N_L / P.
  const std::vector<PathDensity> path{
      {1.0f, 0.5f, false}, {2.0f, 0.25f, false}, {3.0f, 4.0f, false}, {0.5f, 2.0f, false}};
  VcmTechniques first = techniques_of(VcmMode::vcm);
  first.eta = 0.3f;
  const Color value(1.0f, 2.0f, 2.0f);  // |v|^2 = 9
  // p_t = prod_(j < t) pc_j prod_(j >= t) pl_j.
  const auto p = [&](int t) {
    double d = 1.0;
    for (int j = 0; j < 4; ++j) d *= j < t ? path[size_t(j)].camera : path[size_t(j)].light;
    return d;
  };
  // With n camera samples a pixel every technique but light tracing takes n samples.
  const auto q = [&](const VcmBudget& b, int n) {
    if (b.light_paths == 0) return n * (p(3) + p(4));  // next-event estimation and the light hit
    return b.light_paths * p(1) + n * ((b.connect ? p(2) : 0.0) + p(3) + p(4));
  };
  // Light tracing alone makes the second path: pinhole, floor, glass, point light (delta).
  const std::vector<PathDensity> lit = budget_path({false, false, true, true});
  const auto sums = testing::subject([&] {
    std::vector<double> diffuse(kPixelMoments), only_light_tracing(kPixelMoments);
    add_budget_moments(budget_terms(path, {Technique::connection, 3}, first, value), diffuse);
    add_budget_moments(budget_terms(lit, {Technique::connection, 1}, first, value), only_light_tracing);
    return std::make_pair(diffuse, only_light_tracing);
  });
  ASSERT_EQ(sums.first.size(), kPixelMoments);
  ASSERT_EQ(sums.second.size(), kPixelMoments);
  const double q_1 = q(kEveryTechnique, 1), own = p(3);
  for (size_t b = 0; b < kVcmBudgetCount; ++b)
    for (size_t c = 0; c < kCameraSampleChoices; ++c) {
      const int n = kCameraSampleCounts[c];
      const std::string what = describe(kVcmBudgets[b]) + ", " + std::to_string(n) + " camera samples";
      const double expected = 9.0 * own * own / (q_1 * q(kVcmBudgets[b], n));
      EXPECT_NEAR(sums.first[b * kCameraSampleChoices + c], expected, 1e-5 * expected) << what;
      // Without light subpaths the second path is lost; with eight a pixel, its noise is an eighth,
      // whatever the camera samples.
      if (kVcmBudgets[b].light_paths == 0)
        EXPECT_EQ(sums.second[b * kCameraSampleChoices + c], std::numeric_limits<double>::infinity()) << what;
      else
        EXPECT_NEAR(sums.second[b * kCameraSampleChoices + c], 9.0 / kVcmBudgets[b].light_paths, 1e-5) << what;
    }
}

}  // namespace
}  // namespace rt
