#include "06-light-transport/transport_render.h"

#include "01-ray-casting/render.h"
#include "06-light-transport/light_tracer.h"
#include "common/error.h"

#include <stdexcept>

namespace rt {

const char* method_name(TransportMethod method) {
  switch (method) {
    case TransportMethod::pt: return "pt";
    case TransportMethod::lt: return "lt";
    case TransportMethod::bdpt: return "bdpt";
    case TransportMethod::sppm: return "sppm";
  }
  return "?";
}

void check_light_paths_renderable(const SceneDescription& description, const LightingScene& scene, const Camera& camera,
                                  const std::string& what, const std::string& path_tracer,
                                  const std::string& lens_alternative) {
  if (!scene.lights().empty())
    throw InputError(description.source + ": " + what +
                     " starts light paths on area emitters, and a point light has no area: make it a small "
                     "sphere or quad, or render with " +
                     path_tracer);
  if (scene.environment())
    throw InputError(description.source + ": " + what +
                     " does not start light paths on an environment light: render it with " + path_tracer);
  if (scene.emitters().empty())
    throw InputError(description.source + ": " + what + " needs an area emitter to start light paths on");
  if (!lens_alternative.empty() && camera.aperture_radius > 0.0f)
    throw InputError(description.source + ": " + what +
                     " connects light paths to a pinhole, and this camera has an aperture: render it with " +
                     lens_alternative);
}

void check_renderable(const SceneDescription& description, const LightingScene& scene, const Camera& camera,
                      TransportMethod method) {
  if (method == TransportMethod::pt) return;
  check_light_paths_renderable(description, scene, camera, std::string("--method ") + method_name(method),
                               "--method pt", method == TransportMethod::sppm ? "" : "--method pt or sppm");
}

void check_transport_fits(const SceneDescription& description, const RenderSettings& settings,
                          const TransportOptions& options, const MemoryLimit& limit) {
  const double pixels = double(settings.window().area());
  const std::string method = method_name(options.method);
  OtherMemory other{pixels * double(kBytesPerPixel), "the image"};
  if (options.method == TransportMethod::lt || options.method == TransportMethod::bdpt)
    other = {pixels * double(kBytesPerPixel + kSplatBytesPerPixel),
             "the image with " + method + "'s splats, " + std::to_string(kBytesPerPixel + kSplatBytesPerPixel) +
                 " bytes a pixel"};
  if (options.method == TransportMethod::sppm)
    other = {pixels * double(kBytesPerPixel + kSppmBytesPerPixel) +
                 double(options.sppm.photons_per_pass) * double(kSppmBytesPerPhoton),
             "the image with sppm's state, " + std::to_string(kBytesPerPixel + kSppmBytesPerPixel) +
                 " bytes a pixel, and " + std::to_string(options.sppm.photons_per_pass) + " photons a pass at " +
                 std::to_string(kSppmBytesPerPhoton) + " bytes each"};
  check_scene_fits(description.source, triangle_count(description), other, limit);
}

namespace {

// Stage 1's pixel loop (add_pixel_samples, in passes) where each sample may also leave splats
// anywhere on the film: `sample(ray, rng, camera_path, light_path, splats)` returns what it adds to
// its own pixel.
template <class SampleFn>
SampleSums render_with_splats(const Camera& camera, const RenderSettings& settings, int threads, SampleGuard& guard,
                              ProgressBar* progress, SampleFn&& sample) {
  const PixelRect window = settings.window();
  const int width = window.width(), height = window.height();
  const PixelFilter filter(settings.filter);
  SampleSums sums(width, height);
  std::vector<DVec3> splatted(size_t(window.area()), DVec3(0.0));
  // What each tile keeps between its pixels: the splats of this pass, and the two subpaths' vertices.
  struct TileScratch {
    std::vector<Splat> splats;
    std::vector<PathVertex> camera_path, light_path;
  };
  const int tiles_x = (width + kTileSize - 1) / kTileSize, tiles_y = (height + kTileSize - 1) / kTileSize;
  std::vector<TileScratch> tiles(size_t(tiles_x) * size_t(tiles_y));
  render_in_passes(
      width, height, settings.spp, samples_per_pass(window.area(), settings.spp), threads, progress,
      [&](const PixelRect& tile, int x, int y, const PixelPass& pass) {
        TileScratch& t = tiles[size_t(tile.y0 / kTileSize) * size_t(tiles_x) + size_t(tile.x0 / kTileSize)];
        Color sum = sums.sum(x, y);
        const int added = add_pixel_samples<Rng>(
            camera, filter, settings, window.x0 + x, window.y0 + y, pass.begin, pass.end,
            [&](const Ray& ray, Rng& rng) { return guard(sample(ray, rng, t.camera_path, t.light_path, t.splats)); },
            sum);
        sums.set(x, y, sum, sums.count(x, y) + std::uint32_t(added));
        return added;
      },
      [&](const PixelPass&) {
        // The splats, added tile by tile in order: the same sums for any thread count.
        for (TileScratch& t : tiles) {
          for (const Splat& splat : t.splats) {
            const int x = int(splat.film_point.x) - window.x0, y = int(splat.film_point.y) - window.y0;
            if (x < 0 || x >= width || y < 0 || y >= height) continue;
            splatted[size_t(y) * size_t(width) + size_t(x)] += DVec3(guard(splat.value));
          }
          t.splats.clear();
        }
      });
  // Pixel j's light-tracing estimate is (P / N_L) times the sum of its splats: one light path per
  // camera sample, each splat's importance counting the whole film (camera_importance.h).
  const double light_paths = double(sums.total_count());
  if (light_paths > 0.0)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const double share = double(window.area()) * double(sums.count(x, y)) / light_paths;
        const Color splat = Color(splatted[size_t(y) * size_t(width) + size_t(x)] * share);
        sums.set(x, y, sums.sum(x, y) + splat, sums.count(x, y));
      }
  return sums;
}

}  // namespace

SampleSums render_transport(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                            const TransportOptions& options, int threads, SampleGuard& guard, ProgressBar* progress) {
  const bool splats = options.method == TransportMethod::lt || options.method == TransportMethod::bdpt;
  if (splats && settings.filter != PixelFilterType::box)
    throw std::invalid_argument("light tracing splats to the pixel a point lands in: the box filter only");
  switch (options.method) {
    case TransportMethod::pt:
      return render_path_samples(scene, camera, settings, options.path, SamplerKind::sobol, threads, guard, progress);
    case TransportMethod::lt:
      return render_with_splats(camera, settings, threads, guard, progress,
                                [&](const Ray&, Rng& rng, std::vector<PathVertex>&, std::vector<PathVertex>& light_path,
                                    std::vector<Splat>& splats) {
                                  light_tracing_sample(scene, camera, options.bdpt.walk, rng, light_path, splats);
                                  return Color(0.0f);
                                });
    case TransportMethod::bdpt:
      return render_with_splats(camera, settings, threads, guard, progress,
                                [&](const Ray& ray, Rng& rng, std::vector<PathVertex>& camera_path,
                                    std::vector<PathVertex>& light_path, std::vector<Splat>& splats) {
                                  return bdpt_sample(scene, camera, ray, options.bdpt, rng, camera_path, light_path,
                                                     splats);
                                });
    case TransportMethod::sppm: return render_sppm(scene, camera, settings, options.sppm, threads, guard, progress);
  }
  return SampleSums();
}

}  // namespace rt
