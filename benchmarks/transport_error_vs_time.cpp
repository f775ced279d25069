// Writes docs/charts/stage6-error-vs-time.csv, the data behind docs/charts/stage6-error-vs-time.png,
// and the renders behind the equal-time pictures (IMAGE_FOLDER/stage6-<scene>-<method>.pfm, which
// tools/plot_charts.py tiles into docs/images/stage6-<scene>.png): stage 6's methods (path
// tracing, light tracing, BDPT, SPPM) on the four scenes of docs/stage6.md, each at 1, 2, 4, ...
// samples (passes for SPPM) until a render takes longer than kBudgetSeconds, with the wall time,
// the RMSE over the image against the scene's converged reference (assets/references/README.md)
// and the RMSE over the region the scene is about (the caustic, the caustic behind the pane, the
// room beyond the gap; the Cornell box: the whole image). Each picture is the method's last render
// within kPictureSeconds (column `picture`): about the same time for every method.
// Run through tools/make-charts.sh (about 10 minutes on 2 cores), or:
//   build/release/bin/transport_error_vs_time OUT.csv IMAGE_FOLDER
#include "06-light-transport/transport_render.h"
#include "common/image_io.h"
#include "common/metrics.h"
#include "stage6/scene_regions.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace rt::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kBudgetSeconds = 12.0;
constexpr double kPictureSeconds = 2.0;

struct Setup {
  const char* name;
  const char* scene;
  const char* reference;
  int width, height, downsample;  // the reference is `downsample` times the render's size
  PixelRect region;               // what the scene is about
  std::vector<TransportMethod> methods;
};


}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  using namespace rt;
  using namespace rt::bench;
  if (argc != 3 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: transport_error_vs_time OUT.csv IMAGE_FOLDER\n");
    return 2;
  }
  const std::string root = RT_SOURCE_DIR;
  using M = TransportMethod;
  const Setup setups[] = {
      {"cornell-box", "cornell-box.json", "cornell-box-256.pfm", 64, 64, 4, {0, 0, 64, 64}, {M::pt, M::lt, M::bdpt, M::sppm}},
      {"caustic", "caustic.json", "caustic-128x96.pfm", 128, 96, 1, kCausticRegion, {M::pt, M::lt, M::bdpt, M::sppm}},
      {"caustic-through-glass", "caustic-through-glass.json", "caustic-through-glass-128x96.pfm", 128, 96, 1,
       kCausticRegion, {M::pt, M::bdpt, M::sppm}},
      {"light-through-gap", "light-through-gap.json", "light-through-gap-128x96.pfm", 128, 96, 1, kRoomRegion,
       {M::pt, M::bdpt, M::sppm}},
  };
  std::ofstream csv(argv[1]);
  csv << "scene,method,spp,seconds,rmse,region_rmse,picture\n";
  for (const Setup& setup : setups) {
    const SceneDescription description = load_scene(root + "/assets/scenes/" + setup.scene);
    const LightingScene scene(description);
    const Camera camera(description.camera, setup.width, setup.height);
    Image reference = read_pfm(root + "/assets/references/" + setup.reference);
    if (setup.downsample > 1) reference = downsample(reference, setup.downsample);
    std::printf("%s:\n", setup.name);
    for (const M m : setup.methods) {
      TransportOptions options;
      options.method = m;
      options.path.max_depth = options.sppm.max_depth = description.render.max_depth;
      struct Row {
        int spp;
        double seconds, error, region;
      };
      std::vector<Row> rows;
      Image picture;
      int picture_spp = 0;
      for (int spp = 1;; spp *= 2) {
        RenderSettings settings;
        settings.width = setup.width;
        settings.height = setup.height;
        settings.spp = spp;
        settings.seed = 1;
        SampleGuard guard;
        const auto start = Clock::now();
        const Image image = render_transport(scene, camera, settings, options, 0, guard).mean();
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        rows.push_back({spp, seconds, rmse(image, reference), rmse(image, reference, setup.region)});
        std::printf("  %-4s %6d spp %8.2f s  RMSE %.4f  region %.4f\n", method_name(m), spp, seconds,
                    rows.back().error, rows.back().region);
        std::fflush(stdout);
        if (seconds <= kPictureSeconds || picture_spp == 0) {
          picture = image;
          picture_spp = spp;
        }
        if (seconds > kBudgetSeconds) break;
      }
      for (const Row& r : rows)
        csv << setup.name << "," << method_name(m) << "," << r.spp << "," << r.seconds << "," << r.error << ","
            << r.region << "," << (r.spp == picture_spp ? 1 : 0) << "\n";
      write_image(std::filesystem::path(argv[2]) / (std::string("stage6-") + setup.name + "-" + method_name(m) + ".pfm"),
                  picture);
    }
  }
  return csv.good() ? 0 : 1;
}
