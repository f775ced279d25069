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

TEST(VcmBudget, TheChoiceIsTheLeastSecondMomentTimesCost) {
  const VcmWork& work = kWork;
  const double infinite = std::numeric_limits<double>::infinity();
  std::array<double, kVcmBudgetCount> moments{};
  // Each moment the inverse of its cost, so that all products tie at 1, but one a little lower.
  for (size_t b = 0; b < kVcmBudgetCount; ++b) moments[b] = 1.0 / iteration_cost(work, kVcmBudgets[b]);
  const size_t favoured = index_of({1, true, Merging::none});
  moments[favoured] *= 0.99;
  EXPECT_EQ(cheapest_budget(moments, work, 8), kVcmBudgets[favoured]);
  // A budget that would leave light out is never chosen, however cheap.
  moments[favoured] = infinite;
  moments[index_of({0, false, Merging::none})] = infinite;
  const VcmBudget next = cheapest_budget(moments, work, 8);
  EXPECT_NE(next, VcmBudget({1, true, Merging::none}));
  EXPECT_NE(next, VcmBudget({0, false, Merging::none}));
  // Eight light subpaths a pixel are left out where the memory holds one.
  for (size_t b = 0; b < kVcmBudgetCount; ++b)
    moments[b] = (kVcmBudgets[b].light_paths == 8   ? 1e-9
                  : kVcmBudgets[b].light_paths == 0 ? 2.0
                                                    : 1.0) /
                 iteration_cost(work, kVcmBudgets[b]);
  EXPECT_EQ(cheapest_budget(moments, work, 8).light_paths, 8);
  EXPECT_EQ(cheapest_budget(moments, work, 1).light_paths, 1);
  // With no finite estimate at all, every technique.
  moments.fill(infinite);
  EXPECT_EQ(cheapest_budget(moments, work, 1), kEveryTechnique);
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
  // the sum of n p over its connections, written out here. n = 1 but light tracing's, n = N_L / P.
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
  const auto q = [&](const VcmBudget& b) {
    if (b.light_paths == 0) return p(3) + p(4);  // next-event estimation and the light hit
    return b.light_paths * p(1) + (b.connect ? p(2) : 0.0) + p(3) + p(4);
  };
  // Light tracing alone makes the second path: pinhole, floor, glass, point light (delta).
  const std::vector<PathDensity> lit = budget_path({false, false, true, true});
  const auto sums = testing::subject([&] {
    std::array<double, kVcmBudgetCount> diffuse{}, only_light_tracing{};
    add_budget_moments(path, {Technique::connection, 3}, first, value, diffuse);
    add_budget_moments(lit, {Technique::connection, 1}, first, value, only_light_tracing);
    return std::make_pair(std::vector<double>(diffuse.begin(), diffuse.end()),
                          std::vector<double>(only_light_tracing.begin(), only_light_tracing.end()));
  });
  ASSERT_EQ(sums.first.size(), kVcmBudgetCount);
  ASSERT_EQ(sums.second.size(), kVcmBudgetCount);
  const double q_1 = q(kEveryTechnique), own = p(3);
  for (size_t b = 0; b < kVcmBudgetCount; ++b) {
    const double expected = 9.0 * own * own / (q_1 * q(kVcmBudgets[b]));
    EXPECT_NEAR(sums.first[b], expected, 1e-5 * expected) << describe(kVcmBudgets[b]);
    // Without light subpaths the second path is lost; with eight a pixel, its noise is an eighth.
    if (kVcmBudgets[b].light_paths == 0)
      EXPECT_EQ(sums.second[b], std::numeric_limits<double>::infinity());
    else
      EXPECT_NEAR(sums.second[b], 9.0 / kVcmBudgets[b].light_paths, 1e-5) << describe(kVcmBudgets[b]);
  }
}

}  // namespace
}  // namespace rt
