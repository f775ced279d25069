// Writes docs/charts/stage3-accel.csv, the data behind the two stage-3 charts, measured in one run
// on one thread: time per ray (incoherent and coherent rays) for the naive aggregate, each BVH
// builder, the SAH tree collapsed 4-wide (with its leaves slot by slot and as triangle packs), and
// Embree (when installed), on meshes of 10^2 ... 10^6 triangles and the bunny; and each builder's
// build time (the second of two builds, see second_build) and SAH cost. Prints the ratios the
// handout quotes.
// Run through tools/make-charts.sh, or: build/release/bin/accel_scaling OUT.csv
#include "accel_workloads.h"
#include "common/obj_loader.h"

#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <string>

namespace rt::bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Keeps the compiler from dropping the traced rays' results.
volatile size_t g_sink;
void benchmark_keep(size_t value) { g_sink = value; }

// Nanoseconds per ray: passes over `rays` until a quarter of a second has gone by (at least 8
// rays, so that naive on a million triangles still gets measured).
double ns_per_ray(const std::vector<Ray>& rays, const std::function<bool(const Ray&)>& trace) {
  size_t traced = 0, hits = 0;
  const auto start = Clock::now();
  while (traced < 8 || seconds_since(start) < 0.25) {
    hits += trace(rays[traced % rays.size()]) ? 1 : 0;
    ++traced;
  }
  benchmark_keep(hits);
  return seconds_since(start) * 1e9 / double(traced);
}

// Builds twice and keeps the second, timed; the first build's time is dropped. A build's first
// touch of fresh memory costs page faults, and what the process did before (an earlier builder's
// freed arrays, huge pages at hand or not) decides how many: measured after our builders in one
// process, Embree's build took 0.17-0.38 s on the same mesh from run to run. The second build of
// each builder meets the memory its own first one left, so both sides are timed alike.
template <class Build>
auto second_build(Build&& build, double& build_ms) {
  build();
  const auto start = Clock::now();
  auto built = build();
  build_ms = seconds_since(start) * 1e3;
  return built;
}

struct Row {
  std::string accel, mesh;
  size_t triangles;
  double incoherent_ns, coherent_ns, build_ms, sah_cost;
  double bytes_per_triangle;  // the mesh and the structure together
};

void print_row(const Row& r) {
  std::printf("%-16s %-11s %8zu triangles: %9.1f ns/ray incoherent, %9.1f coherent, build %8.1f ms, %6.1f bytes/triangle\n",
              r.accel.c_str(), r.mesh.c_str(), r.triangles, r.incoherent_ns, r.coherent_ns, r.build_ms,
              r.bytes_per_triangle);
  std::fflush(stdout);
}

}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  using namespace rt;
  using namespace rt::bench;
  if (argc != 2) {
    std::fprintf(stderr, "usage: accel_scaling OUT.csv\n");
    return 2;
  }
  std::vector<std::pair<std::string, std::shared_ptr<Primitives>>> meshes;
  for (int e = 2; e <= 6; ++e) meshes.push_back({"sphere 1e" + std::to_string(e), sphere_mesh(std::pow(10.0, e))});
  meshes.push_back({"bunny", single_mesh(load_obj(RT_SOURCE_DIR "/assets/meshes/stanford-bunny.obj"))});

  std::vector<Row> rows;
  std::map<std::pair<std::string, std::string>, double> incoherent;  // (accel, mesh) -> ns
  for (const auto& [name, set] : meshes) {
    const std::vector<Ray> scattered = incoherent_rays(*set, 16384), camera = coherent_rays(*set, 128);
    const double mesh_bytes = double(set->store_of<TriangleKind>().bytes()) / double(set->size());
    auto measure = [&](const std::string& accel, const Aggregate& a, double build_ms, double sah_cost, size_t bytes) {
      auto trace = [&a](const Ray& ray) { return a.closest_hit(ray, Interval::positive()).has_value(); };
      const Row row{accel,      name,     set->size(), ns_per_ray(scattered, trace), ns_per_ray(camera, trace),
                    build_ms,   sah_cost, mesh_bytes + double(bytes) / double(set->size())};
      rows.push_back(row);
      incoherent[{accel, name}] = row.incoherent_ns;
      print_row(row);
    };
    measure("naive", NaiveAggregate(set), 0.0, 0.0, 0);
    for (const SplitMethod split : {SplitMethod::median, SplitMethod::middle, SplitMethod::sah}) {
      BvhBuildOptions o;
      o.split = split;
      double build_ms = 0.0;
      const auto bvh = second_build([&] { return std::make_unique<BvhAggregate<Primitives>>(set, o); }, build_ms);
      measure(split_method_name(split), *bvh, build_ms, bvh->stats().sah_cost, bvh->bytes());
    }
    // The SAH tree collapsed into 4-wide nodes (as stage3 --wide builds it): first with its leaves
    // tested slot by slot, each triangle with its corners in SIMD lanes, then with its leaves stored
    // as triangle packs, four triangles per test, last as compact packs, whose corners are read from
    // the mesh at every test. The binary trees above keep the lecture's scalar test.
    for (const char* layout : {"sah-wide-slots", "sah-wide", "sah-wide-compact"}) {
      BvhBuildOptions o;
      o.wide = true;
      o.triangle_packs = layout != std::string("sah-wide-slots");
      o.compact_packs = layout == std::string("sah-wide-compact");
      TriangleMethod& method = set->store_of<TriangleKind>().method;
      method = TriangleMethod::watertight_lanes;
      double build_ms = 0.0;
      const auto bvh = second_build([&] { return std::make_unique<BvhAggregate<Primitives>>(set, o); }, build_ms);
      measure(layout, *bvh, build_ms, bvh->stats().sah_cost, bvh->bytes());
      method = TriangleMethod::watertight;
    }
#if RT_HAVE_EMBREE
    double build_ms = 0.0;
    const auto embree = second_build([&] { return std::make_unique<EmbreeMesh>(the_mesh(*set)); }, build_ms);
    auto trace = [&embree](const Ray& ray) { return embree->closest_hit(ray).has_value(); };
    // Embree holds its own copy of the mesh: its figure is all it holds.
    const Row row{"embree", name,     set->size(), ns_per_ray(scattered, trace), ns_per_ray(camera, trace),
                  build_ms, 0.0,      double(embree->bytes()) / double(set->size())};
    rows.push_back(row);
    incoherent[{"embree", name}] = row.incoherent_ns;
    print_row(row);
#endif
  }

  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::fprintf(stderr, "accel_scaling: cannot write %s\n", argv[1]);
    return 1;
  }
  std::fprintf(out, "accel,mesh,triangles,incoherent_ns_per_ray,coherent_ns_per_ray,build_ms,sah_cost,bytes_per_triangle\n");
  for (const Row& r : rows)
    std::fprintf(out, "%s,%s,%zu,%.2f,%.2f,%.3f,%.3f,%.1f\n", r.accel.c_str(), r.mesh.c_str(), r.triangles, r.incoherent_ns,
                 r.coherent_ns, r.build_ms, r.sah_cost, r.bytes_per_triangle);
  if (std::fclose(out) != 0) return 1;

  std::printf("\nratios, incoherent rays, one thread, this run:\n");
  for (const char* m : {"sphere 1e5", "sphere 1e6", "bunny"})
    std::printf("  %-11s SAH vs naive %8.0fx   SAH vs median %.2fx   SAH vs middle %.2fx   4-wide vs SAH %.2fx"
                "   packs vs slots %.2fx\n",
                m, incoherent[{"naive", m}] / incoherent[{"sah", m}], incoherent[{"median", m}] / incoherent[{"sah", m}],
                incoherent[{"middle", m}] / incoherent[{"sah", m}], incoherent[{"sah", m}] / incoherent[{"sah-wide", m}],
                incoherent[{"sah-wide-slots", m}] / incoherent[{"sah-wide", m}]);
#if RT_HAVE_EMBREE
  for (const char* m : {"sphere 1e5", "sphere 1e6", "bunny"})
    std::printf("  %-11s SAH reaches %.0f%% of Embree's rays per second, 4-wide SAH %.0f%%, with compact packs %.0f%%;"
                " Embree vs naive %.0fx\n",
                m, 100.0 * incoherent[{"embree", m}] / incoherent[{"sah", m}],
                100.0 * incoherent[{"embree", m}] / incoherent[{"sah-wide", m}],
                100.0 * incoherent[{"embree", m}] / incoherent[{"sah-wide-compact", m}],
                incoherent[{"naive", m}] / incoherent[{"embree", m}]);
#endif
  return 0;
}
