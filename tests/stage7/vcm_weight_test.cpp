// Stage 7's weights: vertex connection and merging's power heuristic over every connection and
// every merge of a path. On random paths of 2 to 6 edges, with delta vertices, each technique's
// weight is the closed form p^2 / sum p^2 over the densities written out in full, the weights of a
// path sum to 1, and without merges they are stage 6's strategy_weight; on the renderer's real
// subpaths the densities of a merged path are those of the connection one vertex shorter.
#include "01-ray-casting/camera_rays.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "07-vcm-mlt/vcm.h"

#include "stage6/loaded_scene.h"
#include "stage6/subpaths.h"
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rt {

// How a subject() hands densities to the judge (tests/support/record.h).
inline auto record_fields(PathDensity& d) { return std::tie(d.camera, d.light, d.delta); }

namespace {

// Connections t = 1 ... k + 1, then merges at x_1 ... x_k-1.
std::vector<Technique> every_technique(int k) {
  std::vector<Technique> out;
  for (int t = 1; t <= k + 1; ++t) out.push_back({Technique::connection, t});
  for (int t = 2; t <= k; ++t) out.push_back({Technique::merge, t});
  return out;
}

std::string describe(Technique m) {
  return std::string(m.kind == Technique::merge ? "merge at x_" : "connection t = ") +
         std::to_string(m.kind == Technique::merge ? m.t - 1 : m.t);
}

TEST(VcmWeight, ByHandOnAThreeVertexPath) {
  // x_0 (pinhole), x_1, x_2 (light) with made-up densities pc (camera side) and pl (light side):
  // the connections t = 1, 2, 3 have densities pl1 pl2, pc1 pl2, pc1 pc2; the merge at x_1,
  // eta pc1 pl1 pl2.
  const float pc1 = 2.0f, pl1 = 0.5f, pc2 = 3.0f, pl2 = 4.0f, eta = 0.7f;
  const std::vector<PathDensity> path{{1.0f, 1.0f, false}, {pc1, pl1, false}, {pc2, pl2, false}};
  const double p[] = {pl1 * pl2, pc1 * pl2, pc1 * pc2, eta * pc1 * pl1 * pl2};
  double sum = 0.0;
  for (const double d : p) sum += d * d;
  const VcmTechniques all{.eta = eta};
  const std::vector<Technique> techniques = every_technique(2);
  const std::vector<float> weights = testing::subject([&] {
    std::vector<float> out;
    for (const Technique m : techniques) out.push_back(vcm_weight(path, m, all));
    // A delta x_1 leaves only the connection that never ends there: t = 3, the light hit.
    std::vector<PathDensity> mirror = path;
    mirror[1].delta = true;
    for (const Technique m : techniques) out.push_back(vcm_weight(mirror, m, all));
    return out;
  });
  ASSERT_EQ(weights.size(), 8u);
  for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(weights[i], p[i] * p[i] / sum, 1e-6) << describe(techniques[i]);
  for (size_t i = 0; i < 4; ++i)
    EXPECT_EQ(weights[4 + i], i == 2 ? 1.0f : 0.0f) << "delta x_1, " << describe(techniques[i]);
}

// A random path of k edges: densities log-uniform over six decades (one in twenty 0, which stands
// for 1), inner vertices delta one time in four.
std::vector<PathDensity> random_path(std::mt19937& random, int k) {
  std::uniform_real_distribution<float> decade(-3.0f, 3.0f), unit(0.0f, 1.0f);
  const auto density = [&] { return unit(random) < 0.05f ? 0.0f : std::pow(10.0f, decade(random)); };
  std::vector<PathDensity> path;
  for (int i = 0; i <= k; ++i) {
    const bool inner = i > 0 && i < k;
    path.push_back({density(), density(), inner && unit(random) < 0.25f});
  }
  return path;
}

// The techniques of `on` that make the path, and each one's density times its samples written out
// in full (0 for one that cannot): p_t = prod_(j < t) pc_j prod_(j >= t) pl_j (light_paths times
// it for t = 1), a merge at x_i eta pl_i p_i+1.
std::vector<double> full_densities(const std::vector<PathDensity>& x, const VcmTechniques& on) {
  const int k = int(x.size()) - 1;
  const auto remap = [](float p) { return double(p != 0.0f ? p : 1.0f); };
  const auto connection = [&](int t) {
    double p = 1.0;
    for (int j = 0; j <= k; ++j) p *= j < t ? remap(x[size_t(j)].camera) : remap(x[size_t(j)].light);
    return p;
  };
  std::vector<double> out;
  for (const Technique m : every_technique(k)) {
    const int t = m.t;
    bool exists;
    if (m.kind == Technique::merge) {
      exists = on.merge && !x[size_t(t - 1)].delta;
    } else if (t == k + 1) {
      exists = on.hit_light && !x[size_t(k)].delta;
    } else {
      exists = (t == 1   ? on.light_trace
                : t == k ? on.next_event
                         : on.connect) &&
               !x[size_t(t - 1)].delta && !x[size_t(t)].delta;
    }
    const double p = m.kind == Technique::merge ? double(on.eta) * remap(x[size_t(t - 1)].light) * connection(t)
                     : t == 1                   ? double(on.light_paths) * connection(t)
                                                : connection(t);
    out.push_back(exists ? p : 0.0);
  }
  return out;
}

TEST(VcmWeight, EveryTechniqueOfARandomPathIsThePowerHeuristicAndTheySumToOne) {
  std::mt19937 random(2012);
  std::uniform_real_distribution<float> log_eta(-3.0f, 3.0f);
  // (what, the closed form's weights, vcm_weight's) per path and set of techniques.
  std::vector<std::tuple<std::string, std::vector<double>, std::vector<PathDensity>, VcmTechniques>> cases;
  for (int n = 0; n < 400; ++n) {
    const int k = 2 + n % 5;
    const VcmMode mode = kVcmModes[size_t(n / 5) % 4];
    VcmTechniques on = techniques_of(mode);
    on.eta = std::pow(10.0f, log_eta(random));
    // Some with eight light subpaths per pixel, some in pixels that take several camera samples
    // (light tracing's samples per camera sample N_L / (P n_p): 8 / 4, 1 / 8), some without
    // next-event estimation (a budget's).
    if (n % 3 == 1) on.light_paths = 8.0f;
    if (n % 3 == 2) on.light_paths = n % 2 ? 2.0f : 0.125f;
    if (n % 7 == 2) on.next_event = false;
    std::vector<PathDensity> path = random_path(random, k);
    cases.emplace_back("path " + std::to_string(n) + " (" + mode_name(mode) + ", k = " + std::to_string(k) + ")",
                       full_densities(path, on), std::move(path), on);
  }
  // Per case and technique: the power heuristic's weight and the balance heuristic's, n p / sum n p
  // (technique_densities' own / sum, what a budget's second moments use).
  const std::vector<std::vector<std::pair<float, double>>> weights = testing::subject([&] {
    std::vector<std::vector<std::pair<float, double>>> out;
    for (const auto& [what, densities, path, on] : cases) {
      std::vector<std::pair<float, double>> w;
      for (const Technique m : every_technique(int(path.size()) - 1)) {
        const TechniqueDensities d = technique_densities(path, m, on);
        w.emplace_back(vcm_weight(path, m, on), d.sum > 0.0 ? d.own / d.sum : 0.0);
      }
      out.push_back(w);
    }
    return out;
  });
  ASSERT_EQ(weights.size(), cases.size());
  int merges_weighed = 0, with_delta = 0;
  for (size_t c = 0; c < cases.size(); ++c) {
    const auto& [what, densities, path, on] = cases[c];
    const std::vector<Technique> techniques = every_technique(int(path.size()) - 1);
    ASSERT_EQ(weights[c].size(), techniques.size()) << what;
    double sum = 0.0, sum2 = 0.0, weight_sum = 0.0, balance_sum = 0.0;
    for (const double p : densities) sum += p, sum2 += p * p;
    for (size_t i = 0; i < techniques.size(); ++i) {
      const auto [power, balance] = weights[c][i];
      const double expected = sum2 > 0.0 ? densities[i] * densities[i] / sum2 : 0.0;
      EXPECT_NEAR(power, expected, 1e-5 + 1e-4 * expected) << what << ", " << describe(techniques[i]);
      const double expected_balance = sum > 0.0 ? densities[i] / sum : 0.0;
      EXPECT_NEAR(balance, expected_balance, 1e-5 + 1e-4 * expected_balance)
          << what << ", " << describe(techniques[i]) << " (balance)";
      weight_sum += power;
      balance_sum += balance;
      merges_weighed += techniques[i].kind == Technique::merge && power > 0.01f;
    }
    if (sum2 > 0.0) {
      EXPECT_NEAR(weight_sum, 1.0, 1e-4) << what;
      EXPECT_NEAR(balance_sum, 1.0, 1e-4) << what;
    }
    for (const PathDensity& d : path) with_delta += d.delta;
  }
  EXPECT_GT(merges_weighed, 100);  // merges took real shares, not only slivers
  EXPECT_GT(with_delta, 100);
}

TEST(VcmWeight, WithoutMergesItIsStage6sStrategyWeight) {
  // Two implementations of the same definition: stage 6 moves vertices across from the strategy
  // (s, t) outward, one subpath at a time.
  std::mt19937 random(1994);
  std::vector<std::tuple<std::string, std::vector<PathDensity>, int>> cases;
  for (int n = 0; n < 300; ++n) {
    const int k = 2 + n % 5;
    std::vector<PathDensity> path = random_path(random, k);
    for (int t = 1; t <= k + 1; ++t) {
      const bool exists = t == k + 1 || (!path[size_t(t - 1)].delta && !path[size_t(t)].delta);
      if (exists) cases.emplace_back("path " + std::to_string(n) + ", t = " + std::to_string(t), path, t);
    }
  }
  const VcmTechniques bpt = techniques_of(VcmMode::bpt);
  const std::vector<std::pair<float, float>> weights = testing::subject([&] {
    std::vector<std::pair<float, float>> out;
    for (const auto& [what, path, t] : cases) {
      const int k = int(path.size()) - 1, s = k + 1 - t;
      std::vector<VertexDensity> camera, light;
      for (int j = 0; j < t; ++j)
        camera.push_back({path[size_t(j)].camera, path[size_t(j)].light, path[size_t(j)].delta});
      for (int j = k; j >= t; --j)
        light.push_back({path[size_t(j)].light, path[size_t(j)].camera, path[size_t(j)].delta});
      camera.back().delta = false;
      if (s > 0) light.back().delta = false;
      out.emplace_back(vcm_weight(path, {Technique::connection, t}, bpt), strategy_weight(camera, light));
    }
    return out;
  });
  ASSERT_EQ(weights.size(), cases.size());
  for (size_t c = 0; c < cases.size(); ++c)
    EXPECT_NEAR(weights[c].first, weights[c].second, 1e-5f + 1e-4f * weights[c].second) << std::get<0>(cases[c]);
}

TEST(VcmWeight, AMergeTakesOverAsEtaGrowsAndVanishesWithIt) {
  // On a diffuse path of 3 edges, the merges' share of the weight grows with eta = N pi r^2: no
  // merge at all for eta = 0, almost all for a huge eta.
  const std::vector<PathDensity> path{{1, 1, false}, {0.5f, 2, false}, {1.5f, 0.8f, false}, {3, 0.3f, false}};
  const std::vector<float> shares = testing::subject([&] {
    std::vector<float> out;
    for (const float eta : {0.0f, 0.01f, 1.0f, 100.0f, 1e6f}) {
      float merged = 0.0f;
      for (const Technique m : every_technique(3))
        if (m.kind == Technique::merge) merged += vcm_weight(path, m, VcmTechniques{.eta = eta});
      out.push_back(merged);
    }
    return out;
  });
  ASSERT_EQ(shares.size(), 5u);
  EXPECT_EQ(shares[0], 0.0f);
  for (size_t i = 1; i < shares.size(); ++i) EXPECT_GT(shares[i], shares[i - 1]) << "eta step " << i;
  EXPECT_GT(shares[4], 0.999f);
}

// The renderer's subpaths in the Cornell box and the caustic scene (glass: delta vertices).
using testing::LoadedScene;
using testing::Subpaths;
Subpaths walk_subpaths(const LoadedScene& s, std::uint64_t k) { return testing::random_subpaths(s, 2012, k); }

const LoadedScene& caustic() {
  static const LoadedScene s("assets/scenes/caustic.json", 64, 48);
  return s;
}

TEST(VcmPaths, ConnectionsWeighAsStage6sBdptAndAMergeIsTheConnectionOneVertexShorter) {
  // (what, vcm_weight of connection_densities with merges off, stage 6's mis_weight) per connection,
  // and (what, t, merge densities, the connection (s - 1, t)'s, y_s-1's pdf_fwd) per merge.
  using Weights = std::vector<std::tuple<std::string, float, float>>;
  using Merges = std::vector<std::tuple<std::string, int, std::vector<PathDensity>, std::vector<PathDensity>, float>>;
  const auto [weights, merges] = testing::subject([] {
    Weights w;
    Merges m;
    std::array<PathDensity, 2 * kMaxSubpathVertices> a, b;
    for (const LoadedScene* s : {&testing::cornell_box<64, 48>(), &caustic()})
      for (std::uint64_t k = 0; k < 150; ++k) {
        const Subpaths p = walk_subpaths(*s, k);
        for (int t = 1; t <= int(p.camera.size()); ++t)
          for (int sl = 0; sl <= int(p.light.size()); ++sl) {
            if (sl + t < 2) continue;
            const std::string what =
                "path " + std::to_string(k) + ", s = " + std::to_string(sl) + ", t = " + std::to_string(t);
            const PathVertex* sampled = sl == 1 ? &p.light[0] : nullptr;
            if (connect_strategy(s->scene, s->camera, p.camera, p.light, sl, t, sampled, {}).value != Color(0.0f))
              w.emplace_back(what,
                             vcm_weight(connection_densities(s->scene, s->camera, p.camera, p.light, sl, t, sampled, a),
                                        {Technique::connection, t}, techniques_of(VcmMode::bpt)),
                             mis_weight(s->scene, s->camera, p.camera, p.light, sl, t, sampled));
            if (sl >= 3 && t >= 2 && !p.camera[size_t(t - 1)].delta && !p.light[size_t(sl - 1)].delta &&
                !p.light[size_t(sl - 2)].delta) {
              const auto merged = merge_densities(s->camera, p.camera, p.light, sl, t, a);
              const auto connected =
                  connection_densities(s->scene, s->camera, p.camera, p.light, sl - 1, t, nullptr, b);
              m.emplace_back(what, t, std::vector(merged.begin(), merged.end()),
                             std::vector(connected.begin(), connected.end()), p.light[size_t(sl - 1)].pdf_fwd);
            }
          }
      }
    return std::pair(w, m);
  });
  for (const auto& [what, vcm, bdpt] : weights) EXPECT_NEAR(vcm, bdpt, 1e-5f + 1e-4f * bdpt) << what;
  EXPECT_GT(weights.size(), 1000u);
  // The merged path has the vertices of the connection (s - 1, t): z_t-1 takes y_s-1's place, and
  // only its density from the light side is y_s-1's, the one the light subpath sampled.
  for (const auto& [what, t, merged, connected, y_fwd] : merges) {
    ASSERT_EQ(merged.size(), connected.size()) << what;
    for (size_t i = 0; i < merged.size(); ++i) {
      EXPECT_EQ(merged[i].camera, connected[i].camera) << what << ", x_" << i;
      EXPECT_EQ(merged[i].light, int(i) == t - 1 ? y_fwd : connected[i].light) << what << ", x_" << i;
      EXPECT_EQ(merged[i].delta, connected[i].delta) << what << ", x_" << i;
    }
  }
  EXPECT_GT(merges.size(), 300u);
}

// A camera subpath to a point of the Cornell box's back wall (Lambertian, albedo rho) and a light
// subpath whose second vertex is made to lie at the same point: what merging them adds.
struct MergeCase {
  Subpaths p;
  Color albedo;
};
MergeCase merge_case(const LoadedScene& s) {
  MergeCase m;
  const Ray ray = generate_camera_ray(s.camera, Vec2(32.0f, 20.0f));
  m.p.camera.push_back(camera_vertex(s.camera));
  WalkSettings walk;
  walk.max_vertices = 2;
  Rng rng(5, 0, 0);
  random_walk(s.scene, ray, Color(1.0f), camera_direction_pdf(s.camera, ray.direction), walk, rng, m.p.camera);
  if (m.p.camera.size() != 2) return m;
  m.albedo = s.scene.material(m.p.camera[1].hit).albedo;
  m.p.light.push_back(*sample_light_vertex(s.scene, 0.5f, Vec2(0.5f)));
  PathVertex y = m.p.camera[1];
  y.beta = Color(2.0f, 3.0f, 4.0f);
  m.p.light.push_back(y);
  return m;
}

TEST(MergeContribution, ThroughputsTimesTheBsdfOverEta) {
  const float eta = 0.25f;
  // (the wall's albedo; the merge, and with the light on the wall's back, a delta light vertex, a
  // delta camera vertex), all made by the renderer's code, so inside subject().
  const auto [albedo, merged] = testing::subject([&] {
    const MergeCase m = merge_case(testing::cornell_box<64, 48>());
    if (m.p.camera.size() != 2) return std::pair(Color(0.0f), std::vector<Color>{});
    std::vector<Color> out{merge_contribution(m.p.camera, m.p.light, 2, 2, eta)};
    Subpaths facing_away = m.p;  // light that reached the wall's back side
    facing_away.light[1].hit.normal = -facing_away.light[1].hit.normal;
    out.push_back(merge_contribution(facing_away.camera, facing_away.light, 2, 2, eta));
    Subpaths mirror = m.p;  // a delta vertex merges with nothing
    mirror.light[1].delta = true;
    out.push_back(merge_contribution(mirror.camera, mirror.light, 2, 2, eta));
    mirror = m.p;
    mirror.camera[1].delta = true;
    out.push_back(merge_contribution(mirror.camera, mirror.light, 2, 2, eta));
    return std::pair(m.albedo, out);
  });
  ASSERT_EQ(merged.size(), 4u);
  // Lambertian: f = rho / pi whatever the directions; beta(z) = 1.
  const Color expected = albedo / kPi * Color(2.0f, 3.0f, 4.0f) / eta;
  EXPECT_GT(albedo.x, 0.5f);  // the white back wall
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(merged[0][c], expected[c], 1e-5f * expected[c]) << "channel " << c;
  EXPECT_EQ(merged[1], Color(0.0f)) << "normals facing apart";
  EXPECT_EQ(merged[2], Color(0.0f)) << "a delta light vertex";
  EXPECT_EQ(merged[3], Color(0.0f)) << "a delta camera vertex";
}

}  // namespace
}  // namespace rt
