// Stage 3 timings (Google Benchmark): time per ray for the naive aggregate and each BVH builder on
// meshes of 10^2 ... 10^6 triangles and on the Stanford bunny, with incoherent and coherent rays,
// on 1 and 2 threads; build time per builder and size; a path tracer's bounce and shadow rays in the
// Cornell box; Embree on the same rays when installed.
// Run: build/release/bin/stage3_bench   (--benchmark_filter=Trace/sah to pick)
#include "accel_workloads.h"
#include "common/obj_loader.h"

#include <benchmark/benchmark.h>

#include <map>
#include <mutex>

namespace rt::bench {
namespace {

// Mesh id: 2..6 = 10^id triangles, 0 = the bunny. Built once and shared by every benchmark.
std::shared_ptr<Primitives> mesh(int id) {
  static std::map<int, std::shared_ptr<Primitives>> cache;
  static std::mutex lock;
  const std::lock_guard<std::mutex> guard(lock);
  auto& set = cache[id];
  if (!set) set = id == 0 ? single_mesh(load_obj(RT_SOURCE_DIR "/assets/meshes/stanford-bunny.obj")) : sphere_mesh(std::pow(10.0, id));
  return set;
}

const std::vector<Ray>& rays(int id, bool coherent) {
  static std::map<std::pair<int, bool>, std::vector<Ray>> cache;
  static std::mutex lock;
  const std::lock_guard<std::mutex> guard(lock);
  auto& r = cache[{id, coherent}];
  if (r.empty()) r = coherent ? coherent_rays(*mesh(id), 128) : incoherent_rays(*mesh(id), 16384);
  return r;
}

// One aggregate per (accelerator, mesh), shared by the threads of a benchmark.
const Aggregate& aggregate(const std::string& accel, int id) {
  static std::map<std::pair<std::string, int>, std::unique_ptr<Aggregate>> cache;
  static std::mutex lock;
  const std::lock_guard<std::mutex> guard(lock);
  auto& a = cache[{accel, id}];
  if (!a) {
    if (accel == "naive") {
      a = std::make_unique<NaiveAggregate<Primitives>>(mesh(id));
    } else {
      BvhBuildOptions o;
      o.split = split_method_from_name(accel);
      a = std::make_unique<BvhAggregate<Primitives>>(mesh(id), o);
    }
  }
  return *a;
}

void trace(benchmark::State& state, const std::string& accel, bool coherent) {
  const int id = int(state.range(0));
  const Aggregate& a = aggregate(accel, id);
  const std::vector<Ray>& r = rays(id, coherent);
  size_t i = size_t(state.thread_index()) * 7919, hits = 0;
  for (auto _ : state) {
    const auto hit = a.closest_hit(r[i % r.size()], Interval::positive());
    hits += hit ? 1 : 0;
    benchmark::DoNotOptimize(hit);
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["triangles"] = double(mesh(id)->size());
  state.counters["ns_per_ray"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
}

const PathRays& cornell_rays() {
  static const PathRays rays = path_rays(RT_SOURCE_DIR "/assets/scenes/cornell-box.json", 1 << 16);
  return rays;
}

template <class Closest, class Occluded>
void cornell_queries(benchmark::State& state, const PathRays& r, bool shadow, Closest&& closest, Occluded&& occluded) {
  size_t i = 0, hits = 0;
  for (auto _ : state) {
    const size_t k = i++ % r.bounce.size();
    const bool hit = shadow ? occluded(r.shadow[k], r.shadow_length[k]) : closest(r.bounce[k], Interval::positive());
    hits += hit ? 1 : 0;
    benchmark::DoNotOptimize(hit);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["ns_per_ray"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
}

void register_all() {
  for (const bool coherent : {false, true}) {
    const std::string kind = coherent ? "coherent" : "incoherent";
    for (const std::string accel : {"naive", "median", "middle", "sah"}) {
      auto* b = benchmark::RegisterBenchmark(("Trace/" + accel + "/" + kind).c_str(),
                                             [accel, coherent](benchmark::State& s) { trace(s, accel, coherent); });
      // Naive costs ~20 ns per triangle per ray; past 10^5 triangles a handful of rays is all it gets.
      for (const int id : {2, 3, 4, 5, 6, 0})
        if (accel != "naive" || id <= 5 || !coherent) b->Arg(id);
      if (accel == "naive") b->MinTime(0.2);
      if (accel == "sah") b->Threads(1)->Threads(2);
      b->UseRealTime();
    }
  }
  // The whole aggregate, on every core: "sah-wide" is what stages 4 and 5 build (collapsed 4-wide,
  // leaves as triangle packs); "embree" the production build on the same mesh.
  for (const std::string builder : {"median", "middle", "sah", "sah-wide"}) {
    auto* b = benchmark::RegisterBenchmark(("Build/" + builder).c_str(), [builder](benchmark::State& s) {
      const auto set = mesh(int(s.range(0)));
      BvhBuildOptions o;
      o.wide = builder == "sah-wide";
      o.split = split_method_from_name(o.wide ? "sah" : builder);
      for (auto _ : s) benchmark::DoNotOptimize(BvhAggregate<Primitives>(set, o));
      s.counters["triangles"] = double(set->size());
    });
    for (const int id : {2, 3, 4, 5, 6, 0}) b->Arg(id);
    b->Unit(benchmark::kMillisecond)->UseRealTime();
  }
  // A path tracer's queries in the Cornell box (its 32 triangles), one thread: each vertex's bounce
  // ray (closest hit) and its shadow ray to the light (any hit), through the tree the renderers
  // build and, below, through Embree. docs/stage5.md (where the time goes) uses the ratio.
  for (const bool shadow : {false, true})
    benchmark::RegisterBenchmark(shadow ? "Cornell/shadow/sah-wide" : "Cornell/bounce/sah-wide", [shadow](benchmark::State& s) {
      const PathRays& r = cornell_rays();
      static const BvhAggregate<Primitives> tree(r.scene, BvhBuildOptions{.wide = true});
      cornell_queries(s, r, shadow, [](const Ray& ray, Interval range) { return tree.closest_hit(ray, range).has_value(); },
                      [](const Ray& ray, float length) { return tree.occluded(ray, Interval{0.0f, length}); });
    });
#if RT_HAVE_EMBREE
  for (const bool shadow : {false, true})
    benchmark::RegisterBenchmark(shadow ? "Cornell/shadow/embree" : "Cornell/bounce/embree", [shadow](benchmark::State& s) {
      const PathRays& r = cornell_rays();
      static const EmbreeMesh embree(the_mesh(*r.scene));
      cornell_queries(s, r, shadow, [](const Ray& ray, Interval) { return embree.closest_hit(ray).has_value(); },
                      [](const Ray& ray, float length) { return embree.occluded(ray, length); });
    });
  auto* embree_build = benchmark::RegisterBenchmark("Build/embree", [](benchmark::State& s) {
    const auto set = mesh(int(s.range(0)));
    for (auto _ : s) benchmark::DoNotOptimize(EmbreeMesh(the_mesh(*set)));
    s.counters["triangles"] = double(set->size());
  });
  for (const int id : {2, 3, 4, 5, 6, 0}) embree_build->Arg(id);
  embree_build->Unit(benchmark::kMillisecond)->UseRealTime();
#endif
#if RT_HAVE_EMBREE
  for (const bool coherent : {false, true}) {
    auto* b = benchmark::RegisterBenchmark((std::string("Trace/embree/") + (coherent ? "coherent" : "incoherent")).c_str(),
                                           [coherent](benchmark::State& s) {
      const int id = int(s.range(0));
      static std::map<int, std::unique_ptr<EmbreeMesh>> cache;
      static std::mutex lock;
      const EmbreeMesh* embree;
      {
        const std::lock_guard<std::mutex> guard(lock);
        auto& e = cache[id];
        if (!e) e = std::make_unique<EmbreeMesh>(the_mesh(*mesh(id)));
        embree = e.get();
      }
      const std::vector<Ray>& r = rays(id, coherent);
      size_t i = size_t(s.thread_index()) * 7919;
      for (auto _ : s) benchmark::DoNotOptimize(embree->closest_hit(r[i++ % r.size()]));
      s.SetItemsProcessed(s.iterations());
      s.counters["ns_per_ray"] = benchmark::Counter(double(s.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    });
    for (const int id : {2, 3, 4, 5, 6, 0}) b->Arg(id);
    b->Threads(1)->Threads(2)->UseRealTime();
  }
#endif
}

}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  rt::bench::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
