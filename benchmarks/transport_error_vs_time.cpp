// Writes docs/charts/stageN-error-vs-time.csv, the data behind docs/charts/stageN-error-vs-time.png,
// and the renders behind the equal-time pictures (IMAGE_FOLDER/stageN-<scene>-<method>.pfm, which
// tools/plot_charts.py tiles into docs/images/stageN-<scene>.png). Stage 6: its methods (path
// tracing, light tracing, BDPT, SPPM) on the four scenes of docs/stage6.md; stage 7: those and
// stage 7's (VCM, multiplexed MLT, Kelemen's PSSMLT) on the same scenes and the room lit through a
// door ajar. Each method runs at 1, 2, 4, ... samples (SPPM passes, VCM iterations, MLT mutations
// per pixel) until a render takes longer than kBudgetSeconds, the methods taking turns, with the
// wall time, the RMSE over the image against the scene's converged reference
// (assets/references/README.md) and the RMSE over the region the scene is about (the caustic, the
// caustic behind the pane, the room beyond the gap; the Cornell box: the whole image). Each picture
// is the method's last render within kPictureSeconds (column `picture`): about the same time for
// every method. Run through tools/make-charts.sh (stage 6 about 10 minutes on 2 cores, stage 7
// about 20), or:
//   build/release/bin/transport_error_vs_time 6|7 OUT.csv IMAGE_FOLDER
#include "06-light-transport/transport_render.h"
#include "07-vcm-mlt/mlt.h"
#include "07-vcm-mlt/vcm.h"
#include "common/image_io.h"
#include "common/metrics.h"
#include "stage6/scene_regions.h"

#include <algorithm>
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
  std::vector<std::string> methods;
};

// The bootstrap of the MLT renders, per path depth for mlt: a fifth of the program's default, so
// that it costs about as much as one of the first renders of the series (it counts in the time).
constexpr int kBootstrap = 20000;

// One render of `method` at `spp` samples, passes, iterations or mutations per pixel.
Image render(const std::string& method, const LightingScene& scene, const Camera& camera,
             const RenderSettings& settings, int max_depth) {
  SampleGuard guard;
  for (const TransportMethod m : kTransportMethods)
    if (method == method_name(m)) {
      TransportOptions options;
      options.method = m;
      options.path.max_depth = options.sppm.max_depth = max_depth;
      return render_transport(scene, camera, settings, options, 0, guard).mean();
    }
  if (method == "vcm") return render_vcm(scene, camera, settings, VcmOptions{}, 0, guard).mean();
  MltOptions options;
  options.multiplexed = method == "mlt";
  options.mutations_per_pixel = settings.spp;
  options.bootstrap = kBootstrap;
  options.max_depth = max_depth;
  return render_mlt(scene, camera, settings, options, 0, guard).mean();
}

}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  using namespace rt;
  using namespace rt::bench;
  const std::string stage = argc == 4 ? argv[1] : "";
  if (argc != 4 || (stage != "6" && stage != "7")) {
    std::fprintf(stderr, "usage: transport_error_vs_time 6|7 OUT.csv IMAGE_FOLDER\n");
    return 2;
  }
  const std::string root = RT_SOURCE_DIR;
  using Methods = std::vector<std::string>;
  const bool seven = stage == "7";
  const auto with_stage7 = [&](Methods m) {
    if (seven) m.insert(m.end(), {"vcm", "mlt", "pssmlt"});
    return m;
  };
  std::vector<Setup> setups = {
      {"cornell-box",
       "cornell-box.json",
       "cornell-box-256.pfm",
       64,
       64,
       4,
       {0, 0, 64, 64},
       with_stage7({"pt", "lt", "bdpt", "sppm"})},
      {"caustic", "caustic.json", "caustic-128x96.pfm", 128, 96, 1, kCausticRegion,
       with_stage7({"pt", "lt", "bdpt", "sppm"})},
      {"caustic-through-glass", "caustic-through-glass.json", "caustic-through-glass-128x96.pfm", 128, 96, 1,
       kCausticRegion, with_stage7({"pt", "bdpt", "sppm"})},
      {"light-through-gap", "light-through-gap.json", "light-through-gap-128x96.pfm", 128, 96, 1, kRoomRegion,
       with_stage7({"pt", "bdpt", "sppm"})},
  };
  if (seven)
    setups.push_back({"door-ajar",
                      "door-ajar.json",
                      "door-ajar-128x96.pfm",
                      128,
                      96,
                      1,
                      {0, 0, 128, 96},
                      with_stage7({"pt", "lt", "bdpt", "sppm"})});
  argv += 1;
  std::ofstream csv(argv[1]);
  csv << "scene,method,spp,seconds,rmse,region_rmse,picture\n";
  for (const Setup& setup : setups) {
    const SceneDescription description = load_scene(root + "/assets/scenes/" + setup.scene);
    const LightingScene scene(description);
    const Camera camera(description.camera, setup.width, setup.height);
    Image reference = read_pfm(root + "/assets/references/" + setup.reference);
    if (setup.downsample > 1) reference = downsample(reference, setup.downsample);
    std::printf("%s:\n", setup.name);
    // The methods take turns, each at 1, 2, 4, ... until its render passes the budget: renders of
    // about the same length run minutes apart at most, so a spell in which this machine runs a
    // fifth slower (docs/stage7.md) falls on all of them alike, not on one method's whole series.
    struct Row {
      int spp;
      double seconds, error, region;
    };
    struct Series {
      std::vector<Row> rows;
      Image picture;
      int picture_spp = 0;
      bool done = false;
    };
    std::vector<Series> series(setup.methods.size());
    for (int spp = 1; std::any_of(series.begin(), series.end(), [](const Series& s) { return !s.done; }); spp *= 2)
      for (size_t i = 0; i < setup.methods.size(); ++i) {
        Series& out = series[i];
        if (out.done) continue;
        const std::string& m = setup.methods[i];
        RenderSettings settings;
        settings.width = setup.width;
        settings.height = setup.height;
        settings.spp = spp;
        settings.seed = 1;
        const auto start = Clock::now();
        const Image image = render(m, scene, camera, settings, description.render.max_depth);
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        out.rows.push_back({spp, seconds, rmse(image, reference), rmse(image, reference, setup.region)});
        std::printf("  %-6s %6d spp %8.2f s  RMSE %.4f  region %.4f\n", m.c_str(), spp, seconds, out.rows.back().error,
                    out.rows.back().region);
        std::fflush(stdout);
        if (seconds <= kPictureSeconds || out.picture_spp == 0) {
          out.picture = image;
          out.picture_spp = spp;
        }
        out.done = seconds > kBudgetSeconds;
      }
    for (size_t i = 0; i < setup.methods.size(); ++i) {
      const std::string& m = setup.methods[i];
      for (const Row& r : series[i].rows)
        csv << setup.name << "," << m << "," << r.spp << "," << r.seconds << "," << r.error << "," << r.region << ","
            << (r.spp == series[i].picture_spp ? 1 : 0) << "\n";
      write_image(std::filesystem::path(argv[2]) / ("stage" + stage + "-" + setup.name + "-" + m + ".pfm"),
                  series[i].picture);
    }
  }
  return csv.good() ? 0 : 1;
}
