#include "07-vcm-mlt/vcm.h"

#include "01-ray-casting/camera_rays.h"
#include "01-ray-casting/render.h"
#include "05-path-tracing/path_tracer.h"
#include "05-path-tracing/sobol_sampler.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "common/interrupt.h"
#include "common/parallel.h"
#include "common/task.h"

#include <algorithm>
#include <array>

namespace rt {

const char* mode_name(VcmMode mode) {
  switch (mode) {
    case VcmMode::vcm:
      return "vcm";
    case VcmMode::bpt:
      return "bpt";
    case VcmMode::ppm:
      return "ppm";
    case VcmMode::lt:
      return "lt";
  }
  return "?";
}

VcmTechniques techniques_of(VcmMode mode) {
  switch (mode) {
    case VcmMode::vcm:
      return {};
    case VcmMode::bpt:
      return {.merge = false};
    case VcmMode::ppm:
      return {.light_trace = false, .connect = false};
    case VcmMode::lt:
      return {.hit_light = false, .connect = false, .merge = false};
  }
  return {};
}

float merge_radius(float initial_radius, int iteration, float alpha) {
  return initial_radius * std::pow(float(std::max(iteration, 1)), 0.5f * (alpha - 1.0f));
}

float default_merge_radius(const LightingScene& scene, const Camera& camera) {
  // The first hits of a coarse grid of rays through pixel centres: a fixed set, so the radius is
  // the same in every run.
  constexpr int kGrid = 16;
  std::vector<float> distances;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Vec2 film((float(i) + 0.5f) * float(camera.width) / kGrid,
                      (float(j) + 0.5f) * float(camera.height) / kGrid);
      const Ray ray = generate_camera_ray(camera, film);
      if (const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive()))
        distances.push_back(hit->t * glm::length(ray.direction));
    }
  if (distances.empty()) return 1.0f;  // nothing visible: any radius renders the same black
  std::nth_element(distances.begin(), distances.begin() + std::ptrdiff_t(distances.size() / 2), distances.end());
  const float pixel_angle = 2.0f * camera.tan_half_vfov / float(camera.height);
  return kVcmFootprintRadii * pixel_angle * std::max(distances[distances.size() / 2], 1e-30f);
}

std::span<const PathDensity> connection_densities(const LightingScene& scene, const Camera& camera,
                                                  std::span<const PathVertex> camera_path,
                                                  std::span<const PathVertex> light_path, int s, int t,
                                                  const PathVertex* sampled_light, std::span<PathDensity> out) {
  // x_0 ... x_t-1 = z_0 ... z_t-1, then x_t ... x_s+t-1 = y_s-1 ... y_0.
  const auto light_vertex_at = [&](int i) -> const PathVertex& {
    return i == 0 && sampled_light ? *sampled_light : light_path[size_t(i)];
  };
  for (int i = 0; i < t; ++i) {
    const PathVertex& z = camera_path[size_t(i)];
    out[size_t(i)] = {z.pdf_fwd, z.pdf_rev, z.delta};
  }
  for (int i = 0; i < s; ++i) {
    const PathVertex& y = light_vertex_at(i);
    out[size_t(t + s - 1 - i)] = {y.pdf_rev, y.pdf_fwd, y.delta};
  }
  // The joined path's densities around the connection (stage 6's mis_weight).
  const PathVertex& z = camera_path[size_t(t - 1)];
  const PathVertex* z_before = t > 1 ? &camera_path[size_t(t - 2)] : nullptr;
  const PathVertex* y = s > 0 ? &light_vertex_at(s - 1) : nullptr;
  const PathVertex* y_before = s > 1 ? &light_path[size_t(s - 2)] : nullptr;
  out[size_t(t - 1)].light = y ? vertex_pdf(camera, *y, y_before, z) : light_origin_pdf(scene, z);
  out[size_t(t - 1)].delta = false;
  if (z_before)
    out[size_t(t - 2)].light = y ? vertex_pdf(camera, z, y, *z_before) : light_emission_pdf(scene, z, *z_before);
  if (y) {
    out[size_t(t)].camera = vertex_pdf(camera, z, z_before, *y);
    out[size_t(t)].delta = false;
  }
  if (y_before) out[size_t(t + 1)].camera = vertex_pdf(camera, *y, &z, *y_before);
  return out.first(size_t(s + t));
}

std::span<const PathDensity> merge_densities(const Camera& camera, std::span<const PathVertex> camera_path,
                                             std::span<const PathVertex> light_path, int s, int t,
                                             std::span<PathDensity> out) {
  // x_0 ... x_t-1 = z_0 ... z_t-1, x_t-1 also y_s-1, then x_t ... x_s+t-2 = y_s-2 ... y_0.
  for (int i = 0; i < t; ++i) {
    const PathVertex& z = camera_path[size_t(i)];
    out[size_t(i)] = {z.pdf_fwd, z.pdf_rev, z.delta};
  }
  for (int i = 0; i < s - 1; ++i) {
    const PathVertex& y = light_path[size_t(i)];
    out[size_t(t + s - 2 - i)] = {y.pdf_rev, y.pdf_fwd, y.delta};
  }
  const PathVertex& z = camera_path[size_t(t - 1)];
  const PathVertex& z_before = camera_path[size_t(t - 2)];
  const PathVertex& y_before = light_path[size_t(s - 2)];
  out[size_t(t - 1)] = {z.pdf_fwd, light_path[size_t(s - 1)].pdf_fwd, false};
  // z scatters between its two neighbours, in either direction, and y_s-2 now arrives from z.
  out[size_t(t - 2)].light = vertex_pdf(camera, z, &y_before, z_before);
  out[size_t(t)].camera = vertex_pdf(camera, z, &z_before, y_before);
  if (s > 2) out[size_t(t + 1)].camera = vertex_pdf(camera, y_before, &z, light_path[size_t(s - 3)]);
  return out.first(size_t(s + t - 1));
}

Color merge_contribution(std::span<const PathVertex> camera_path, std::span<const PathVertex> light_path, int s, int t,
                         float eta) {
  // BEGIN TASK stage7.vcm.merge
  const PathVertex& z = camera_path[size_t(t - 1)];
  const PathVertex& y = light_path[size_t(s - 1)];
  if (z.delta || y.delta || !(eta > 0.0f) || glm::dot(z.normal(), y.normal()) <= 0.0f) return Color(0.0f);
  const Color f = scattering(z, z.direction_to(camera_path[size_t(t - 2)]), y.direction_to(light_path[size_t(s - 2)]));
  return z.beta * f * y.beta / eta;
  // PLACEHOLDER
  // report_unfinished_task("stage7.vcm.merge");
  // (void)camera_path, (void)light_path, (void)s, (void)t, (void)eta;
  // return Color(0.0f);  // no merges: --mode vcm renders as bpt
  // END TASK
}

void check_vcm_fits(const SceneDescription& description, const RenderSettings& settings, const MemoryLimit& limit) {
  const double pixels = double(settings.width) * double(settings.height);
  check_scene_fits(description.source, triangle_count(description),
                   {pixels * double(kBytesPerPixel + kVcmBytesPerPixel),
                    "the image with an iteration's light subpaths, " +
                        std::to_string(kBytesPerPixel + kVcmBytesPerPixel) + " bytes a pixel"},
                   limit);
}

namespace {

// Light subpaths per unit of parallel work: fixed, so each subpath's numbers and the order of the
// splats and photons never depend on the thread count.
constexpr int kLightPathsPerChunk = 256;
// The random stream light subpaths draw from (Rng's "pixel" argument): no pixel has this index.
constexpr std::uint64_t kLightStream = ~std::uint64_t(0);

using DensityScratch = std::array<PathDensity, 2 * kMaxSubpathVertices>;

// The techniques that can make a path of k + 1 vertices. The light's own point seen by the pinhole
// (k = 1: x_0 the pinhole, x_1 on the light) is splatted only where the camera's own rays cannot
// do better. Inside a lamp's image the camera's ray sees a constant emitter without noise, while
// the N light points scattered over the lamp land in its pixels in random numbers; the power
// heuristic reads densities, not variances, and gives the splats almost all the weight there (each
// of N points is likelier to fall on a given spot than the pixel's one ray), and with it their
// count's noise: at 64 x 64 pixels three quarters of the Cornell box's squared error. At the lamp's
// edges a pixel's coverage is what the camera's rays estimate, well only if they are stratified:
// with independent camera numbers the splats do better there, by far. So with Sobol camera
// subpaths the camera alone takes these paths, its weight then 1 (PBR 3rd ed.'s BDPT, section
// 16.3, always leaves this strategy out); with independent ones, and where the camera cannot hit
// lights (--mode lt), the splats count too.
VcmTechniques techniques_for(VcmTechniques on, int k, SamplerKind camera_sampler) {
  if (k == 1 && on.hit_light && camera_sampler == SamplerKind::sobol) on.light_trace = false;
  return on;
}

// What one chunk of light subpaths leaves: the subpaths (subpath j of the chunk is
// vertices[begin[j], begin[j + 1])) and their light-tracing splats.
struct LightChunk {
  std::vector<PathVertex> vertices;
  std::vector<std::uint32_t> begin{0};
  std::vector<Splat> splats;
  std::span<const PathVertex> path(size_t j) const {
    return std::span(vertices).subspan(begin[j], begin[j + 1] - begin[j]);
  }
};

// An iteration's light subpaths, left in the chunks that traced them (one copy: a light vertex
// holds its BSDF, some 270 bytes), numbered across the chunks in order: subpath j is the one of
// pixel j, and a vertex's number is the photon's `source`.
class LightSubpaths {
 public:
  explicit LightSubpaths(const std::vector<LightChunk>& chunks) : chunks_(chunks) {
    std::uint32_t first = 0;
    for (const LightChunk& c : chunks) {
      first_vertex_.push_back(first);
      first += std::uint32_t(c.vertices.size());
    }
  }
  std::span<const PathVertex> path(size_t j) const {
    return chunks_[j / kLightPathsPerChunk].path(j % kLightPathsPerChunk);
  }
  // Vertex number v: its subpath, and its index in it plus 1 (s, the strategy's light vertices).
  std::pair<std::span<const PathVertex>, int> vertex(std::uint32_t v) const {
    const size_t c =
        size_t(std::upper_bound(first_vertex_.begin(), first_vertex_.end(), v) - first_vertex_.begin()) - 1;
    const LightChunk& chunk = chunks_[c];
    const std::uint32_t local = v - first_vertex_[c];
    const size_t j = size_t(std::upper_bound(chunk.begin.begin(), chunk.begin.end(), local) - chunk.begin.begin()) - 1;
    return {chunk.path(j), int(local - chunk.begin[j]) + 1};
  }
  // Every light vertex that can merge (not the light's own, not a delta one), as a photon, in `out`.
  void photons(std::vector<Photon>& out) const {
    out.clear();
    for (size_t c = 0; c < chunks_.size(); ++c) {
      const LightChunk& chunk = chunks_[c];
      for (size_t j = 0; j + 1 < chunk.begin.size(); ++j)
        for (std::uint32_t v = chunk.begin[j] + 1; v < chunk.begin[j + 1]; ++v) {
          const PathVertex& y = chunk.vertices[v];
          if (!y.delta && is_finite(y.beta))
            out.push_back(Photon{y.point(), y.direction_to(chunk.vertices[v - 1]), y.beta, first_vertex_[c] + v});
        }
    }
  }

 private:
  const std::vector<LightChunk>& chunks_;
  std::vector<std::uint32_t> first_vertex_;
};

class VcmIteration {
 public:
  VcmIteration(const LightingScene& scene, const Camera& camera, const VcmOptions& options, VcmTechniques on,
               float radius)
      : scene_(scene), camera_(camera), options_(options), on_(on), radius_(radius) {}

  // Light subpath j: traced (in `scratch`), kept, and each vertex seen by the camera splatted.
  void trace_light_path(Rng& rng, std::vector<PathVertex>& scratch, LightChunk& out) const {
    std::vector<PathVertex>& vertices = out.vertices;
    const size_t first = vertices.size();
    scratch.clear();
    if (const std::optional<LightSubpathStart> start = start_light_subpath(scene_, rng, options_.walk.offset)) {
      scratch.push_back(start->origin);
      WalkSettings walk = options_.walk;
      walk.mode = TransportMode::importance;
      random_walk(scene_, start->ray, start->beta, start->pdf_w, walk, rng, scratch);
      vertices.insert(vertices.end(), scratch.begin(), scratch.end());
    }
    out.begin.push_back(std::uint32_t(vertices.size()));
    if (!on_.light_trace) return;
    const std::span<const PathVertex> path = std::span(vertices).subspan(first);
    const PathVertex eye = camera_vertex(camera_);
    DensityScratch densities_of;
    for (int s = 1; s <= int(path.size()); ++s) {
      const VcmTechniques techniques = techniques_for(on_, s, options_.camera_sampler);
      if (!techniques.light_trace) continue;
      const StrategySample r =
          connect_strategy(scene_, camera_, std::span(&eye, 1), path, s, 1, nullptr, options_.walk.offset);
      if (!r.film_point || r.value == Color(0.0f)) continue;
      const auto densities =
          connection_densities(scene_, camera_, std::span(&eye, 1), path, s, 1, nullptr, densities_of);
      out.splats.push_back(
          Splat{*r.film_point, r.value * vcm_weight(densities, {Technique::connection, 1}, techniques)});
    }
  }

  // The camera sample along `ray`, against light subpath `light_path` and the grid of all of them.
  Color camera_sample(const Ray& ray, Sampler& sampler, std::span<const PathVertex> light_path,
                      const LightSubpaths& all, const PhotonGrid* grid, std::vector<PathVertex>& camera_path) const {
    camera_path.assign(1, camera_vertex(camera_));
    WalkSettings walk = options_.walk;
    walk.mode = TransportMode::radiance;
    random_walk(scene_, ray, Color(1.0f), camera_direction_pdf(camera_, ray.direction), walk, sampler, camera_path);
    const OffsetPolicy& offset = options_.walk.offset;
    DensityScratch scratch;
    Color radiance(0.0f);
    for (int t = 2; t <= int(camera_path.size()); ++t) {
      const PathVertex& z = camera_path[size_t(t - 1)];
      if (on_.hit_light && z.emitter >= 0) {
        const StrategySample r = connect_strategy(scene_, camera_, camera_path, light_path, 0, t, nullptr, offset);
        if (r.value != Color(0.0f))
          radiance += r.value *
                      vcm_weight(connection_densities(scene_, camera_, camera_path, light_path, 0, t, nullptr, scratch),
                                 {Technique::connection, t}, techniques_for(on_, t - 1, options_.camera_sampler));
      }
      if (z.delta) continue;
      if (on_.connect) {
        const float u_choice = sampler.uniform();
        const std::optional<PathVertex> fresh = sample_light_vertex(scene_, u_choice, sampler.uniform2());
        for (int s = 1; s <= std::max(1, int(light_path.size())); ++s) {
          const PathVertex* light_point = s == 1 ? (fresh ? &*fresh : nullptr) : nullptr;
          if (s == 1 && !light_point) continue;
          const StrategySample r =
              connect_strategy(scene_, camera_, camera_path, light_path, s, t, light_point, offset);
          if (r.value == Color(0.0f)) continue;
          radiance += r.value * vcm_weight(connection_densities(scene_, camera_, camera_path, light_path, s, t,
                                                                light_point, scratch),
                                           {Technique::connection, t}, on_);
        }
      }
      if (grid) {
        grid->for_each_within(z.point(), radius_, [&](const Photon& photon) {
          const auto [y_path, s] = all.vertex(photon.source);
          const Color value = merge_contribution(camera_path, y_path, s, t, on_.eta);
          if (value == Color(0.0f)) return;
          radiance += value * vcm_weight(merge_densities(camera_, camera_path, y_path, s, t, scratch),
                                         {Technique::merge, t}, on_);
        });
      }
    }
    return radiance;
  }

 private:
  const LightingScene& scene_;
  const Camera& camera_;
  const VcmOptions& options_;
  VcmTechniques on_;
  float radius_;
};

}  // namespace

SampleSums render_vcm(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                      const VcmOptions& options, int threads, SampleGuard& guard, ProgressBar* progress) {
  const int width = camera.width, height = camera.height;
  const size_t pixels = size_t(width) * size_t(height);
  const PixelFilter filter(settings.filter);
  const float initial_radius =
      options.initial_radius > 0.0f ? options.initial_radius : default_merge_radius(scene, camera);
  const int chunks = int((pixels + kLightPathsPerChunk - 1) / kLightPathsPerChunk);
  std::vector<LightChunk> chunk(size_t(chunks), LightChunk{});
  std::vector<Color> film(pixels, Color(0.0f));     // each pixel's camera samples, summed over the iterations
  std::vector<DVec3> splatted(pixels, DVec3(0.0));  // the splats landing in it, summed
  std::vector<Color> this_film(pixels);
  std::vector<DVec3> this_splatted(pixels);
  std::vector<Photon> photons;  // each iteration's, and their grid: kept, their memory reused
  PhotonGrid grid;
  std::uint32_t iterations = 0;
  for (int i = 0; i < settings.spp && !interrupt_requested(); ++i) {
    VcmTechniques on = techniques_of(options.mode);
    const float radius = merge_radius(initial_radius, i + 1, options.alpha);
    on.eta = float(double(pixels) * double(kPi) * double(radius) * double(radius));
    const VcmIteration iteration(scene, camera, options, on, radius);

    // The light subpaths, chunk by chunk, then in one list in chunk order.
    parallel_for(chunks, threads, [&](int c) {
      LightChunk& out = chunk[size_t(c)];
      out.vertices.clear();
      out.begin.assign(1, 0);
      out.splats.clear();
      std::vector<PathVertex> scratch;
      const size_t first = size_t(c) * kLightPathsPerChunk, last = std::min(pixels, first + kLightPathsPerChunk);
      for (size_t j = first; j < last && !interrupt_requested(); ++j) {
        Rng rng(settings.seed, kLightStream, std::uint64_t(i) * pixels + j);
        iteration.trace_light_path(rng, scratch, out);
      }
    });
    if (interrupt_requested()) break;
    const LightSubpaths all(chunk);
    if (on.merge) {
      all.photons(photons);
      grid.assign(std::span(&photons, 1), 2.0f * radius);
    }

    // The camera subpaths, one per pixel, each against its own light subpath and the grid.
    const bool camera_paths = on.hit_light || on.connect || on.merge;
    parallel_for_tiles(width, height, threads, [&](const PixelRect& tile) {
      std::vector<PathVertex> camera_path;
      for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
          const size_t p = size_t(y) * size_t(width) + size_t(x);
          Color sum(0.0f);
          const auto sample = [&](const Ray& ray, Sampler& sampler) {
            return guard(
                iteration.camera_sample(ray, sampler, all.path(p), all, on.merge ? &grid : nullptr, camera_path));
          };
          if (camera_paths && options.camera_sampler == SamplerKind::sobol)
            add_pixel_samples<SobolSampler>(camera, filter, settings, x, y, i, i + 1, sample, sum);
          else if (camera_paths)
            add_pixel_samples<Rng>(camera, filter, settings, x, y, i, i + 1, sample, sum);
          this_film[p] = sum;
        }
    });
    if (interrupt_requested()) break;
    // Pixel j's light-tracing estimate is (P / N_L) times its splats' sum, one light subpath per
    // pixel: each iteration's splats count once (camera_importance.h).
    std::fill(this_splatted.begin(), this_splatted.end(), DVec3(0.0));
    for (const LightChunk& c : chunk)
      for (const Splat& splat : c.splats) {
        const int x = int(splat.film_point.x), y = int(splat.film_point.y);
        if (x < 0 || x >= width || y < 0 || y >= height) continue;
        this_splatted[size_t(y) * size_t(width) + size_t(x)] += DVec3(guard(splat.value));
      }
    for (size_t p = 0; p < pixels; ++p) {
      film[p] += this_film[p];
      splatted[p] += this_splatted[p];
    }
    ++iterations;
    if (progress) progress->advance(pixels);
  }
  SampleSums sums(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * size_t(width) + size_t(x);
      if (iterations > 0) sums.set(x, y, film[p] + Color(splatted[p]), iterations);
    }
  return sums;
}

}  // namespace rt
