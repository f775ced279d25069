// Stage 6's bookkeeping: the area densities a random walk stores in both directions, and the MIS
// weights built from them. Every density a walk stored is recomputed from the vertices' geometry
// and BSDFs, and on random full paths the weights of all strategies that could make the path sum
// to 1 and equal the power heuristic's closed form p_s^2 / sum_i p_i^2.
#include "01-ray-casting/camera_rays.h"
#include "06-light-transport/bdpt.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"

#include "stage6/loaded_scene.h"
#include "stage6/subpaths.h"
#include "support/glowing_room.h"
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace rt {
namespace {

using testing::LoadedScene;

const LoadedScene& cornell() { return testing::cornell_box<64, 48>(); }
const LoadedScene& caustic() {
  static const LoadedScene s("assets/scenes/caustic.json", 64, 48);
  return s;
}

using testing::Subpaths;
Subpaths subpaths(const LoadedScene& s, std::uint64_t k, int max_vertices = 6) {
  return testing::random_subpaths(s, 77, k, max_vertices);
}

void expect_relative(double actual, double expected, double tolerance, const std::string& what) {
  EXPECT_NEAR(actual, expected, tolerance * std::max(std::abs(expected), 1e-30)) << what;
}

TEST(AreaDensity, SolidAngleTimesCosineOverDistanceSquared) {
  PathVertex from, to;
  from.hit.point = Vec3(0.0f);
  to.hit.point = Vec3(0.0f, 0.0f, 2.0f);
  to.hit.normal = glm::normalize(Vec3(0.0f, 1.0f, -1.0f));  // 45 degrees to the incoming direction
  EXPECT_NEAR(RT_GRADED(to_area_density)(0.8f, from, to), 0.8f * std::sqrt(0.5f) / 4.0f, 1e-6f);
  to.hit.normal = Vec3(0.0f, 0.0f, 1.0f);  // facing away: the density needs |cos|
  EXPECT_NEAR(RT_GRADED(to_area_density)(0.8f, from, to), 0.2f, 1e-6f);
  to.hit.normal = Vec3(1.0f, 0.0f, 0.0f);  // edge-on: no area density
  EXPECT_EQ(RT_GRADED(to_area_density)(0.8f, from, to), 0.0f);
  // The pinhole has no area: towards it the density is per unit solid angle over distance squared.
  to.kind = VertexKind::camera;
  EXPECT_NEAR(RT_GRADED(to_area_density)(0.8f, from, to), 0.2f, 1e-6f);
}

// (what, stored, recomputed): what the walk stored against what the geometry says, for every
// vertex whose neighbours exist.
using Densities = std::vector<std::tuple<std::string, float, float>>;
void walk_densities(const LoadedScene& s, const std::vector<PathVertex>& path, const std::string& what,
                    Densities& out) {
  for (size_t i = 1; i < path.size(); ++i) {
    const PathVertex& before = path[i - 1];
    const float fwd = vertex_pdf(s.camera, before, i >= 2 ? &path[i - 2] : nullptr, path[i]);
    out.emplace_back(what + " pdf_fwd of vertex " + std::to_string(i), path[i].pdf_fwd, fwd);
  }
  for (size_t i = 0; i + 2 < path.size(); ++i) {
    const float rev = vertex_pdf(s.camera, path[i + 1], &path[i + 2], path[i]);
    out.emplace_back(what + " pdf_rev of vertex " + std::to_string(i), path[i].pdf_rev, rev);
  }
}

TEST(RandomWalk, StoresTheDensitiesOfBothDirections) {
  const auto [densities, long_walks] = testing::subject([] {
    Densities out;
    int deep = 0;
    for (const LoadedScene* s : {&cornell(), &caustic()})
      for (std::uint64_t k = 0; k < 200; ++k) {
        const Subpaths p = subpaths(*s, k);
        walk_densities(*s, p.camera, "camera subpath " + std::to_string(k), out);
        walk_densities(*s, p.light, "light subpath " + std::to_string(k), out);
        deep += p.camera.size() >= 4 && p.light.size() >= 4;
      }
    return std::pair(out, deep);
  });
  for (const auto& [what, stored, recomputed] : densities) {
    expect_relative(stored, recomputed, 1e-3, what);
    if (what.find("pdf_fwd") != std::string::npos) {
      EXPECT_GT(stored, 0.0f) << what;
    }
  }
  EXPECT_GT(long_walks, 40);  // the check saw many deep vertices, not only first hits
}

TEST(RandomWalk, ThroughputIsTheProductOfTheSamplingWeights) {
  // In the Cornell box every surface is Lambertian: a cosine-sampled bounce has weight = albedo, so
  // the camera subpath's beta at vertex i is the product of the albedos before it (and the light
  // subpath's the emitted flux over the choice times the same product).
  const LoadedScene& s = cornell();
  // (what, beta.y the walk carried, the product of the albedos before it, tolerance).
  const auto [betas, vertices] = testing::subject([&] {
    std::vector<std::tuple<std::string, float, float, float>> out;
    size_t count = 0;
    for (std::uint64_t k = 0; k < 50; ++k) {
      const Subpaths p = subpaths(s, k);
      count += p.camera.size() + p.light.size();
      Color beta(1.0f);
      for (size_t i = 1; i < p.camera.size(); ++i) {
        out.emplace_back(std::to_string(k) + ", " + std::to_string(i), p.camera[i].beta.y, beta.y, 1e-4f);
        beta *= s.scene.material(p.camera[i].hit).albedo;
      }
      if (p.light.size() < 2) continue;
      const AreaEmitter& e = s.scene.emitters().at(size_t(p.light[0].emitter));
      Color flux = e.radiance * (kPi * e.area() / s.scene.emitter_distribution().pmf(p.light[0].emitter));
      for (size_t i = 1; i < p.light.size(); ++i) {
        out.emplace_back(std::to_string(k) + ", light " + std::to_string(i), p.light[i].beta.y, flux.y, 1e-3f);
        flux *= s.scene.material(p.light[i].hit).albedo;
      }
    }
    return std::pair(out, std::uint64_t(count));
  });
  for (const auto& [what, carried, product, tolerance] : betas)
    EXPECT_NEAR(carried, product, tolerance * product) << what;
  EXPECT_GT(vertices, 300u);  // 50 camera and 50 light subpaths of up to 6 vertices: most go deep
}

// Russian roulette starts after settings.roulette_start bounces, as in stage 5. In a closed room
// of albedo 0.5 no walk leaves the scene, so before roulette none ends, and at its first chance,
// after `start` bounces of weight 0.5, a walk survives with probability 0.5^start
// (survival_probability): with roulette_start 2 the shortest camera subpaths have exactly three
// vertices (the camera and two hits), and 3/4 of them are that short. A roulette started a bounce
// early or late moves that shortest length; the image's expectation does not tell, roulette being
// unbiased. The light subpaths the same: their throughput starts at the emitted flux, and it is the
// throughput relative to that start that roulette reads.
TEST(RandomWalk, RouletteStartsAfterRouletteStartBounces) {
  static const LoadedScene room(parse_scene(testing::kGlowingRoom, "glowing-room.json"), 8, 8);
  for (const bool light : {false, true})
    for (const int start : {1, 2, 4}) {
      WalkSettings walk;
      walk.roulette_start = start;
      walk.mode = light ? TransportMode::importance : TransportMode::radiance;
      // (length, walks of that length), shortest first; nothing where a light subpath could not start.
      const auto histogram = testing::subject([&]() -> std::optional<std::vector<std::pair<std::uint64_t, int>>> {
        std::map<size_t, int> counted;
        for (std::uint64_t k = 0; k < 400; ++k) {
          Rng rng(91, 0, k);
          std::vector<PathVertex> path;
          if (light) {
            const std::optional<LightSubpathStart> s = start_light_subpath(room.scene, rng, walk.offset);
            if (!s) return std::nullopt;
            path.push_back(s->origin);
            random_walk(room.scene, s->ray, s->beta, s->pdf_w, walk, rng, path);
          } else {
            const Ray ray = generate_camera_ray(room.camera, Vec2(rng.uniform() * 8.0f, rng.uniform() * 8.0f));
            path.push_back(camera_vertex(room.camera));
            random_walk(room.scene, ray, Color(1.0f), camera_direction_pdf(room.camera, ray.direction), walk, rng,
                        path);
          }
          ++counted[path.size()];
        }
        return std::vector<std::pair<std::uint64_t, int>>(counted.begin(), counted.end());
      });
      ASSERT_TRUE(histogram && !histogram->empty());
      const std::map<size_t, int> lengths(histogram->begin(), histogram->end());
      const std::string what = std::string(light ? "light" : "camera") + " subpaths, roulette_start " +
                               std::to_string(start);
      EXPECT_EQ(lengths.begin()->first, size_t(start + 1)) << what << ": the shortest walk";
      const double survive = std::pow(0.5, start);
      EXPECT_NEAR(lengths.begin()->second, 400.0 * (1.0 - survive), 5.0 * std::sqrt(400.0 * survive * (1.0 - survive)))
          << what << ": the walks that end at the first roulette";
    }
}

// A walk stops at settings.max_vertices vertices, its start included, and one asked for no more
// than the path already has adds nothing (BDPT's one-strategy renders ask for exactly that: a light
// subpath of its start alone). The glowing room is closed, so every walk runs to its length.
TEST(RandomWalk, NeverLongerThanMaxVertices) {
  static const LoadedScene room(parse_scene(testing::kGlowingRoom, "glowing-room.json"), 8, 8);
  for (const int max_vertices : {1, 2, 3, 5}) {
    const std::vector<std::uint64_t> lengths = testing::subject([&] {
      std::vector<std::uint64_t> out;
      for (std::uint64_t k = 0; k < 20; ++k) {
        Rng rng(93, 0, k);
        WalkSettings walk;
        walk.max_vertices = max_vertices;
        walk.roulette_start = 100;
        std::vector<PathVertex> path{camera_vertex(room.camera)};
        const Ray ray = generate_camera_ray(room.camera, Vec2(rng.uniform() * 8.0f, rng.uniform() * 8.0f));
        random_walk(room.scene, ray, Color(1.0f), camera_direction_pdf(room.camera, ray.direction), walk, rng, path);
        out.push_back(path.size());
      }
      return out;
    });
    for (const std::uint64_t n : lengths) EXPECT_EQ(n, std::uint64_t(max_vertices)) << "max_vertices " << max_vertices;
  }
}

// A full path x_0 (camera) ... x_k (on a light), each vertex with its density from either side.
struct FullPath {
  std::vector<const PathVertex*> x;
  std::vector<double> from_camera, from_light;
};

FullPath join(const LoadedScene& s, const Subpaths& p, int sl, int tc, const PathVertex* sampled_light) {
  FullPath f;
  for (int i = 0; i < tc; ++i) f.x.push_back(&p.camera[size_t(i)]);
  for (int i = sl - 1; i >= 0; --i) f.x.push_back(i == 0 && sampled_light ? sampled_light : &p.light[size_t(i)]);
  const size_t n = f.x.size();
  f.from_camera.assign(n, 1.0);
  f.from_light.assign(n, 1.0);
  for (size_t i = 1; i < n; ++i) f.from_camera[i] = vertex_pdf(s.camera, *f.x[i - 1], i >= 2 ? f.x[i - 2] : nullptr, *f.x[i]);
  f.from_light[n - 1] = light_origin_pdf(s.scene, *f.x[n - 1]);
  if (n >= 2) f.from_light[n - 2] = light_emission_pdf(s.scene, *f.x[n - 1], *f.x[n - 2]);
  for (size_t i = 0; i + 2 < n; ++i) f.from_light[i] = vertex_pdf(s.camera, *f.x[i + 1], f.x[i + 2], *f.x[i]);
  return f;
}

// Strategy (s, t) of a full path exists when t >= 1 and neither end of its connection is a delta.
bool strategy_exists(const FullPath& f, int s) {
  const int t = int(f.x.size()) - s;
  if (t < 1) return false;
  if (s == 0) return f.x.back()->emitter >= 0;
  return !f.x[size_t(t - 1)]->delta && !f.x[size_t(t)]->delta;
}

// The weight the reference densities give strategy s through stage 6's strategy_weight.
float reference_weight(const FullPath& f, int s) {
  const int n = int(f.x.size()), t = n - s;
  std::vector<VertexDensity> camera, light;
  for (int i = 0; i < t; ++i)
    camera.push_back({float(f.from_camera[size_t(i)]), float(f.from_light[size_t(i)]), f.x[size_t(i)]->delta});
  for (int j = 0; j < s; ++j) {
    const size_t i = size_t(n - 1 - j);
    light.push_back({float(f.from_light[i]), float(f.from_camera[i]), f.x[i]->delta});
  }
  if (t >= 1) camera.back().delta = false;
  if (s >= 1) light.back().delta = false;
  return RT_GRADED(strategy_weight)(camera, light);
}

TEST(MisWeights, EveryStrategyOfAPathSumsToOneAndTheRendererAgrees) {
  // Per connected path: (what, the sum of the reference weights of its strategies, the renderer's
  // weight, the reference weight of its own strategy, s + t).
  using Weights = std::vector<std::tuple<std::string, double, float, float, int>>;
  const auto [weights, with_delta] = testing::subject([] {
    Weights out;
    int deltas = 0;
    for (const LoadedScene* s : {&cornell(), &caustic()})
      for (std::uint64_t k = 0; k < 300; ++k) {
        const Subpaths p = subpaths(*s, k);
        if (p.light.empty()) continue;
        for (int t = 1; t <= int(p.camera.size()); ++t)
          for (int sl = 0; sl <= int(p.light.size()); ++sl) {
            if (sl + t < 2) continue;
            const PathVertex* sampled = sl == 1 ? &p.light[0] : nullptr;
            const StrategySample r = connect_strategy(s->scene, s->camera, p.camera, p.light, sl, t, sampled, {});
            if (r.value == Color(0.0f)) continue;  // no path: nothing to weigh
            const FullPath f = join(*s, p, sl, t, sampled);
            double sum = 0.0;
            for (int other = 0; other <= int(f.x.size()); ++other)
              if (strategy_exists(f, other)) sum += reference_weight(f, other);
            out.emplace_back("path " + std::to_string(k) + ", s = " + std::to_string(sl) + ", t = " + std::to_string(t),
                             sum, mis_weight(s->scene, s->camera, p.camera, p.light, sl, t, sampled),
                             reference_weight(f, sl), sl + t);
            for (const PathVertex* v : f.x) deltas += v->delta;
          }
      }
    return std::pair(out, deltas);
  });
  for (const auto& [what, sum, renderer, reference, vertices] : weights) {
    EXPECT_NEAR(sum, 1.0, 1e-4) << what;
    // The renderer reads the densities its walks stored, computed from the sampled directions;
    // the reference recomputes them from the rounded vertex positions. Each pair agrees within
    // 1e-3 (RandomWalk.StoresTheDensitiesOfBothDirections) and a weight is a ratio of products
    // of up to s + t of them on each side.
    EXPECT_NEAR(renderer, reference, 2e-3f * float(vertices) * std::max(renderer, 1e-3f)) << what;
  }
  EXPECT_GT(weights.size(), 1000u);
  EXPECT_GT(with_delta, 50);  // glass vertices took part
}

TEST(MisWeights, ThePowerHeuristicsClosedFormOnDiffusePaths) {
  // Without delta vertices every strategy exists and p_s is the plain product of densities.
  const LoadedScene& s = cornell();
  // Per path k checked: the five strategies' weights and their densities from either side.
  const auto paths = testing::subject([&] {
    std::vector<std::tuple<std::uint64_t, std::vector<float>, std::vector<double>>> out;
    for (std::uint64_t k = 0; k < 200; ++k) {
      const Subpaths p = subpaths(s, k, 4);
      if (p.camera.size() < 3 || p.light.size() < 2) continue;
      if (connect_strategy(s.scene, s.camera, p.camera, p.light, 2, 3, nullptr, {}).value == Color(0.0f)) continue;
      const FullPath f = join(s, p, 2, 3, nullptr);  // 5 vertices: strategies s = 0 ... 4
      std::vector<float> weights;
      for (int sl = 0; sl <= 4; ++sl) weights.push_back(reference_weight(f, sl));
      std::vector<double> sides(f.from_camera);
      sides.insert(sides.end(), f.from_light.begin(), f.from_light.end());
      out.emplace_back(k, weights, sides);
    }
    return out;
  });
  for (const auto& [k, weights, sides] : paths) {
    ASSERT_EQ(weights.size(), 5u);
    ASSERT_EQ(sides.size(), 10u);
    std::vector<double> density;
    for (int sl = 0; sl <= 4; ++sl) {
      double d = 1.0;
      for (int i = 0; i < 5; ++i) d *= i < 5 - sl ? sides[size_t(i)] : sides[size_t(5 + i)];
      density.push_back(d);
    }
    double sum2 = 0.0;
    for (const double d : density) sum2 += d * d;
    for (int sl = 0; sl <= 4; ++sl)
      EXPECT_NEAR(weights[size_t(sl)], density[size_t(sl)] * density[size_t(sl)] / sum2, 1e-4) << k << ", " << sl;
  }
  EXPECT_GT(paths.size(), 20u);
}

TEST(MisWeights, ByHandOnAThreeVertexPath) {
  // z_0 (pinhole), z_1, y_0 with made-up densities: strategies s = 0, 1, 2 have densities
  // p_0 = a1 b2, p_1 = a1 c2, p_2 = c1 c2 (a: camera side, c: light side).
  const float a1 = 2.0f, b2 = 3.0f, c1 = 0.5f, c2 = 4.0f;
  const double p0 = a1 * b2, p1 = a1 * c2, p2 = c1 * c2, sum = p0 * p0 + p1 * p1 + p2 * p2;
  const VertexDensity z0{1.0f, 0.0f, false}, z1_t2{a1, c1, false};
  // s = 1, t = 2: z_1 (fwd a1, rev c1); y_0 (fwd c2, rev b2).
  EXPECT_NEAR(RT_GRADED(strategy_weight)(std::vector{z0, z1_t2}, std::vector{VertexDensity{c2, b2, false}}),
              p1 * p1 / sum, 1e-6);
  // s = 0, t = 3: y_0 is the camera's third vertex (fwd b2, rev c2).
  EXPECT_NEAR(
      RT_GRADED(strategy_weight)(std::vector{z0, z1_t2, VertexDensity{b2, c2, false}}, std::vector<VertexDensity>{}),
      p0 * p0 / sum, 1e-6);
  // s = 2, t = 1: z_1 on the light side (fwd c1, rev a1).
  EXPECT_NEAR(RT_GRADED(strategy_weight)(std::vector{z0},
                                         std::vector{VertexDensity{c2, b2, false}, VertexDensity{c1, a1, false}}),
              p2 * p2 / sum, 1e-6);
  // A delta z_1 leaves only the strategy that never connects at it: s = 0 takes all.
  const VertexDensity z1_delta{0.0f, 0.0f, true};
  EXPECT_NEAR(
      RT_GRADED(strategy_weight)(std::vector{z0, z1_delta, VertexDensity{b2, c2, false}}, std::vector<VertexDensity>{}),
      1.0, 1e-6);
}

}  // namespace
}  // namespace rt
