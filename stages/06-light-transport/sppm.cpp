#include "06-light-transport/sppm.h"

#include "01-ray-casting/camera_rays.h"
#include "05-path-tracing/sobol_sampler.h"
#include "06-light-transport/light_emission.h"
#include "06-light-transport/photon_grid.h"
#include "common/pixel_passes.h"
#include "common/random.h"
#include "common/task.h"

namespace rt {

void progressive_update(PhotonStatistics& stats, int found, Color flux, float alpha) {
  // BEGIN TASK stage6.sppm.update
  if (found <= 0) return;
  const double kept = stats.photons + double(alpha) * double(found);
  const float shrink = float(kept / (stats.photons + double(found)));  // r_i+1^2 / r_i^2
  stats.tau = (stats.tau + flux) * shrink;
  stats.radius *= std::sqrt(shrink);
  stats.photons = kept;
  // PLACEHOLDER
  // report_unfinished_task("stage6.sppm.update");
  // stats.tau += flux;  // no reduction: the radius, and so the blur, never shrinks
  // stats.photons += double(found);
  // (void)alpha;
  // END TASK
}

Color photon_radiance(const PhotonStatistics& stats, double photons_emitted) {
  const double area = kPi * double(stats.radius) * double(stats.radius);
  if (!(area > 0.0) || !(photons_emitted > 0.0)) return Color(0.0f);
  return stats.tau / float(area * photons_emitted);
}

Gathered gather_photons(const PhotonGrid& grid, const ShadingPoint& at, float radius) {
  Gathered g;
  // BEGIN TASK stage6.sppm.gather
  grid.for_each_within(at.hit.point, radius, [&](const Photon& photon) {
    ++g.found;
    g.flux += photon.power * at.bsdf.eval(at.wo, at.frame.to_local(photon.wi));
  });
  // PLACEHOLDER
  // report_unfinished_task("stage6.sppm.gather");
  // (void)grid, (void)at, (void)radius;
  // END TASK
  return g;
}

namespace {

// Photons per unit of parallel work: fixed, so each photon's numbers and the order photons are
// stored in never depend on the thread count.
constexpr int kPhotonsPerChunk = 1024;
// The random stream photons draw from (Rng's "pixel" argument): no pixel has this index.
constexpr std::uint64_t kPhotonStream = ~std::uint64_t(0);

struct VisiblePoint {
  std::optional<ShadingPoint> at;
  Color beta{0.0f};
  float distance = 0.0f;  // along the camera path, through any mirrors and glass
};

// A camera path through delta lobes to its first other surface. Adds to `light` what it sees
// emitted on the way (and the background, if it leaves) and the direct light at that surface.
VisiblePoint trace_visible_point(const LightingScene& scene, Ray ray, const SppmOptions& options, SobolSampler& sampler,
                                 Color& light) {
  Color beta(1.0f);
  float distance = 0.0f;
  for (int depth = 0; depth <= options.max_depth; ++depth) {
    const Vec2 u = sampler.uniform2();
    const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
    if (!hit) {
      light += beta * scene.background();
      return {};
    }
    light += beta * scene.emitted(*hit);
    distance += hit->t * glm::length(ray.direction);
    const ShadingPoint at = make_shading_point(scene, *hit, -ray.direction);
    if (!at.bsdf.is_delta()) {
      light += beta * sample_direct_light(scene, at, sampler, options.walk.offset).value;
      return {at, beta, distance};
    }
    const std::optional<BsdfSample> s = at.bsdf.sample(at.wo, u, sampler.uniform());
    if (!s) return {};
    beta *= s->weight;
    ray = spawn_ray(*hit, at.frame.to_world(s->wi), options.walk.offset);
  }
  return {};
}

// One photon: a light subpath, and a photon left at each of its vertices after the first bounce
// that is not a delta lobe. The first surface a light reaches is lit directly, which the visible
// point's light sample already counts.
void trace_photon(const LightingScene& scene, const SppmOptions& options, Rng& rng, std::vector<PathVertex>& path,
                  std::vector<Photon>& photons) {
  path.clear();
  const std::optional<LightSubpathStart> start = start_light_subpath(scene, rng, options.walk.offset);
  if (!start) return;
  path.push_back(start->origin);
  WalkSettings walk = options.walk;
  walk.mode = TransportMode::importance;
  random_walk(scene, start->ray, start->beta, start->pdf_w, walk, rng, path);
  for (size_t i = 2; i < path.size(); ++i) {
    const PathVertex& v = path[i];
    if (v.delta || !is_finite(v.beta)) continue;
    photons.push_back(Photon{v.point(), v.direction_to(path[i - 1]), v.beta});
  }
}

}  // namespace

SampleSums render_sppm(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                       const SppmOptions& options, int threads, SampleGuard& guard, ProgressBar* progress) {
  const PixelRect window = settings.window();
  const int width = window.width(), height = window.height();
  const size_t pixels = size_t(window.area());
  // r_0: the given radius, or (radius 0 until then) kFootprintRadii pixel footprints at the pixel's
  // first visible point: a pixel's width in radians times the distance the camera path travelled.
  const float pixel_angle = 2.0f * camera.tan_half_vfov / float(camera.height);
  std::vector<PhotonStatistics> stats(pixels, PhotonStatistics{0.0, std::max(options.initial_radius, 0.0f), Color(0.0f)});
  std::vector<Color> light(pixels, Color(0.0f));  // emitted and direct light, summed over the passes
  std::vector<Color> light_with_pass(light);      // the same with the pass under way, kept once it ends
  std::vector<VisiblePoint> visible(pixels);
  const int chunks = (options.photons_per_pass + kPhotonsPerChunk - 1) / kPhotonsPerChunk;
  std::vector<std::vector<Photon>> chunk_photons(static_cast<size_t>(chunks));
  PhotonGrid grid;  // each pass's photons, in one grid's memory

  // A stop (Ctrl-C) is checked inside a pass, per tile and per chunk of photons, since one pass of
  // 10^7 photons takes many seconds: a pass it cuts short is dropped whole, and the image is made
  // of the passes that ended. A pass is one camera path per pixel, then the photons.
  int passes = 0;
  render_in_passes(
      width, height, settings.spp, 1, threads, nullptr,
      [&](const PixelRect&, int x, int y, const PixelPass& p) {
        const std::uint64_t pass = std::uint64_t(settings.first_sample + p.begin);
        const int px = window.x0 + x, py = window.y0 + y;
        // Scrambled Sobol points over the passes (stage 5's sampler): one camera path per pixel and
        // pass, so the passes' film points stratify the pixel, which an edge (the lamp's, in the
        // Cornell box) needs; independent points left such pixels the noisiest of the image.
        SobolSampler sampler(settings.seed, std::uint64_t(py) * std::uint64_t(camera.width) + std::uint64_t(px), pass);
        const Vec2 film = Vec2(float(px), float(py)) + sampler.uniform2();
        const Ray ray = camera.aperture_radius > 0.0f ? generate_lens_ray(camera, film, sampler.uniform2())
                                                      : generate_camera_ray(camera, film);
        const size_t i = size_t(y) * size_t(width) + size_t(x);
        visible[i] = trace_visible_point(scene, ray, options, sampler, light_with_pass[i]);
        if (visible[i].at && stats[i].radius == 0.0f)
          stats[i].radius = kFootprintRadii * pixel_angle * std::max(visible[i].distance, 1e-30f);
        return 0;
      },
      [&](const PixelPass& p) {
        if (interrupt_requested()) return;
        const std::uint64_t pass = std::uint64_t(settings.first_sample + p.begin);
        float max_radius = 0.0f;
        for (size_t i = 0; i < pixels; ++i)
          if (visible[i].at) max_radius = std::max(max_radius, stats[i].radius);
        parallel_for(chunks, threads, [&](int c) {
          std::vector<Photon>& out = chunk_photons[size_t(c)];
          out.clear();
          std::vector<PathVertex> path;
          const int first = c * kPhotonsPerChunk, last = std::min(options.photons_per_pass, first + kPhotonsPerChunk);
          if (interrupt_requested()) return;
          for (int j = first; j < last; ++j) {
            Rng rng(settings.seed, kPhotonStream, pass * std::uint64_t(options.photons_per_pass) + std::uint64_t(j));
            trace_photon(scene, options, rng, path, out);
          }
        });
        if (interrupt_requested()) return;
        if (max_radius > 0.0f) {
          grid.assign(chunk_photons, 2.0f * max_radius);
          if (interrupt_requested()) return;
          parallel_for_tiles(width, height, threads, [&](const PixelRect& tile) {
            for (int y = tile.y0; y < tile.y1; ++y)
              for (int x = tile.x0; x < tile.x1; ++x) {
                const size_t i = size_t(y) * size_t(width) + size_t(x);
                if (!visible[i].at) continue;
                const Gathered g = gather_photons(grid, *visible[i].at, stats[i].radius);
                progressive_update(stats[i], g.found, visible[i].beta * g.flux, options.alpha);
              }
          });
        }
        light = light_with_pass;  // the pass ended: its light is kept, and the next one adds to it
        ++passes;
        if (progress) progress->advance(pixels);
      });

  SampleSums sums(width, height);
  const double emitted = double(passes) * double(options.photons_per_pass);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      if (passes == 0) continue;
      const Color estimate = guard(light[i] / float(passes) + photon_radiance(stats[i], emitted));
      sums.set(x, y, estimate * float(passes), std::uint32_t(passes));
    }
  return sums;
}

}  // namespace rt
