// stage3: renders a scene like stage 2, with the bounded primitives in a chosen acceleration
// structure, and reports what the structure cost and what it bought.
#include "01-ray-casting/render.h"
#include "02-whitted/whitted.h"
#include "03-acceleration/bvh_aggregate.h"
#include "common/stage_program.h"

#include <atomic>
#include <chrono>
#include <cstdio>

namespace rt {
namespace {

// Counts the rays an aggregate answers (closest-hit and shadow queries alike) for the rays/s figure.
class CountingAggregate : public Aggregate {
 public:
  explicit CountingAggregate(std::unique_ptr<Aggregate> inner) : inner_(std::move(inner)) {}
  std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const override {
    rays_.fetch_add(1, std::memory_order_relaxed);
    return inner_->closest_hit(ray, range);
  }
  bool occluded(const Ray& ray, Interval range) const override {
    rays_.fetch_add(1, std::memory_order_relaxed);
    return inner_->occluded(ray, range);
  }
  const Aggregate& inner() const { return *inner_; }
  std::uint64_t rays() const { return rays_.load(); }

 private:
  std::unique_ptr<Aggregate> inner_;
  mutable std::atomic<std::uint64_t> rays_{0};
};

}  // namespace
}  // namespace rt

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  std::string debug_name = "none", accel_name = "sah";
  int leaf_size = 4;
  bool wide = false, compact = false;

  return run_stage_program(
      argc, argv, "stage3", "Stage 3: Whitted ray tracing over a bounding volume hierarchy", options,
      [&](StageFlags& flags) {
        flags.add_max_depth(options, "the mirror and glass bounces a ray is followed through");
        flags.add_word("--accel", accel_name, {"naive", "median", "middle", "sah"},
                       "Acceleration structure: naive (every primitive), median, middle or sah");
        flags.add("--leaf-size", leaf_size, "Largest leaf a BVH builder makes without trying to split",
                  decimal_in(1, 255));
        flags.add_switch("--wide", wide,
                         "Traverse a 4-wide tree collapsed from the binary one (four box tests at once), testing "
                         "triangles with their corners in SIMD lanes");
        flags.add_switch("--compact", compact,
                         "With --wide: store each leaf's triangles as vertex numbers in their mesh and read the "
                         "corners from it at every test (40 % less memory; leaves that mix meshes stay slots)",
                         "--wide");
        flags.add_word("--debug", debug_name, {"none", "normal", "depth", "albedo"},
                       "Debug view instead of shading: none, normal, depth, albedo");
      },
      [&] {
        const DebugView view = debug_view_from_name(debug_name);
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        BvhBuildOptions build;
        build.max_leaf_size = leaf_size;
        build.wide = wide;
        build.compact_packs = compact;
        const bool naive = accel_name == "naive";
        if (!naive) build.split = split_method_from_name(accel_name);

        const auto build_start = std::chrono::steady_clock::now();
        const CountingAggregate* counter = nullptr;
        // The 4-wide tree goes with the triangle test in SIMD lanes: both are the speed ladder's
        // (docs/stage3.md); the binary trees keep the lecture's scalar test.
        const TriangleMethod triangle_method = wide ? TriangleMethod::watertight_lanes : TriangleMethod::watertight;
        const WhittedScene scene(description, triangle_method, [&](std::shared_ptr<const WhittedPrimitives> p) {
          auto inner = naive ? naive_aggregate_factory<WhittedPrimitives>()(std::move(p))
                             : bvh_aggregate_factory<WhittedPrimitives>(build)(std::move(p));
          auto counting = std::make_unique<CountingAggregate>(std::move(inner));
          counter = counting.get();
          return counting;
        });
        const double build_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();

        const size_t triangles = scene.triangle_count();
        const size_t spheres = SphereKind::size(scene.primitives().store_of<SphereKind>());
        std::printf("stage3: %zu triangles, %zu spheres; accelerator %s", triangles, spheres, accel_name.c_str());
        if (const auto* bvh = dynamic_cast<const BvhAggregate<WhittedPrimitives>*>(&counter->inner())) {
          const BvhStats s = bvh->stats();
          const size_t mesh_bytes = scene.primitives().store_of<TriangleKind>().bytes();
          std::printf(" (leaf size %d%s), built in %.3f s\n", leaf_size, wide ? ", 4-wide" : "", build_seconds);
          std::printf("stage3: %zu nodes, %zu leaves, depth %zu, primitives per leaf %.2f mean / %zu max, SAH cost %.1f\n",
                      s.nodes, s.leaves, s.depth, s.mean_leaf_primitives, s.max_leaf_primitives, s.sah_cost);
          if (bvh->wide_bvh())
            std::printf("stage3: collapsed into %zu 4-wide nodes, %zu leaves stored as %s triangle packs\n",
                        bvh->wide_bvh()->nodes.size(), bvh->packs(), compact ? "compact" : "copied");
          if (triangles > 0)
            std::printf("stage3: memory %.1f bytes per triangle (mesh %.1f + BVH %.1f)\n",
                        double(mesh_bytes + bvh->bytes()) / double(triangles), double(mesh_bytes) / double(triangles),
                        double(bvh->bytes()) / double(triangles));
        } else {
          std::printf(", nothing to build\n");
        }

        WhittedOptions whitted;
        whitted.max_depth = settings.max_depth;
        const Camera camera(description.camera, settings.width, settings.height);
        const auto render_start = std::chrono::steady_clock::now();
        render_and_write("stage3", options, description, settings, camera, meaning_of(view), [&](const Ray& ray, Rng&) {
          return view == DebugView::none ? whitted_radiance(scene, ray, whitted) : whitted_debug(scene, ray, view);
        });
        const double render_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
        std::printf("stage3: %s rays traced, %s rays/s\n", format_si(double(counter->rays())).c_str(),
                    format_si(double(counter->rays()) / render_seconds).c_str());
      });
}
