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
#include <atomic>

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
      return {.light_trace = false, .next_event = false, .connect = false};
    case VcmMode::lt:
      return {.hit_light = false, .next_event = false, .connect = false, .merge = false};
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

int check_vcm_fits(const SceneDescription& description, const RenderSettings& settings, const MemoryLimit& limit) {
  const double pixels = double(settings.width) * double(settings.height);
  const auto needs = [&](int light_paths) -> OtherMemory {
    const std::uint64_t per_pixel =
        kBytesPerPixel + std::max(std::uint64_t(light_paths) * kVcmBytesPerPixel,
                                  kVcmBytesPerPixel + kVcmChoiceBytesPerPixel);  // the first iteration's
    return {pixels * double(per_pixel),
            "the image with an iteration's light subpaths, " + std::to_string(per_pixel) + " bytes a pixel"};
  };
  constexpr int kMost = kVcmBudgets[kVcmBudgetCount - 1].light_paths;
  try {
    check_scene_fits(description.source, triangle_count(description), needs(kMost), limit);
    return kMost;
  } catch (const InputError&) {
    check_scene_fits(description.source, triangle_count(description), needs(1), limit);
    return 1;
  }
}

namespace {

// Light subpaths per unit of parallel work: fixed, so each subpath's numbers and the order of the
// splats and photons never depend on the thread count.
constexpr int kLightPathsPerChunk = 256;
// The random stream light subpaths draw from (Rng's "pixel" argument): no pixel has this index.
constexpr std::uint64_t kLightStream = ~std::uint64_t(0);

using DensityScratch = std::array<PathDensity, 2 * kMaxSubpathVertices>;

// Pixel p's camera samples an iteration, of a plan's (`camera_samples`; empty: one each).
int camera_samples_at(std::span<const std::uint8_t> camera_samples, size_t pixel) {
  return camera_samples.empty() ? 1 : camera_samples[pixel];
}

// The pixel a film point lies in, if any: where a splat lands.
std::optional<size_t> pixel_of(const Camera& camera, Vec2 film_point) {
  const int x = int(film_point.x), y = int(film_point.y);
  if (film_point.x < 0.0f || film_point.y < 0.0f || x >= camera.width || y >= camera.height) return std::nullopt;
  return size_t(y) * size_t(camera.width) + size_t(x);
}

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
  std::vector<BudgetTerms> terms;  // each splat's terms of the second moments, in the first iteration
  std::span<const PathVertex> path(size_t j) const {
    return std::span(vertices).subspan(begin[j], begin[j + 1] - begin[j]);
  }
};

// An iteration's light subpaths, left in the chunks that traced them (one copy: a light vertex
// holds its BSDF, some 270 bytes), numbered across the chunks in order: subpath j < P is the one
// pixel j connects to (those after it, when a budget traces more, only splat and merge), and a
// vertex's number is the photon's `source`.
class LightSubpaths {
 public:
  explicit LightSubpaths(std::span<const LightChunk> chunks) : chunks_(chunks) {
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
  // Each vertex v of each subpath that `is_photon(subpath, v)` takes, as a photon, in `out`.
  template <class IsPhoton>
  void photons(std::vector<Photon>& out, IsPhoton is_photon) const {
    out.clear();
    for (size_t c = 0; c < chunks_.size(); ++c) {
      const LightChunk& chunk = chunks_[c];
      for (size_t j = 0; j + 1 < chunk.begin.size(); ++j) {
        const std::span<const PathVertex> path = chunk.path(j);
        for (size_t v = 1; v < path.size(); ++v)
          if (is_photon(path, v))
            out.push_back(Photon{path[v].point(), path[v].direction_to(path[v - 1]), path[v].beta,
                                 first_vertex_[c] + chunk.begin[j] + std::uint32_t(v)});
      }
    }
  }

 private:
  std::span<const LightChunk> chunks_;
  std::vector<std::uint32_t> first_vertex_;
};

// Whether the connection that would join a merged vertex to `before`, the vertex before it on one
// subpath, is on and can end there: then it makes every path that merge could make, and a budget
// that merges only where needed skips the merge (vcm_budget.h). A subpath's first vertex (the
// camera, the light's point) is joined by its own technique (light tracing, next-event
// estimation), on or off as `first_technique` says.
bool joined(const PathVertex& before, bool before_is_first, bool first_technique, bool connect) {
  return (before_is_first ? first_technique : connect) && !before.delta;
}

// The first iteration's work, counted as it goes (vcm_budget.h).
struct WorkCounters {
  std::atomic<std::uint64_t> camera_vertices{0}, light_points{0}, light_subpaths{0}, light_vertices{0}, camera_links{0},
      connections{0};
  // A chosen budget's photons and merges, with connections [1] and without [0].
  std::array<std::atomic<std::uint64_t>, 2> photons{}, merges{};
  VcmWork work() const {
    return {camera_vertices, light_points, light_subpaths,          light_vertices,
            camera_links,    connections,  {photons[1], merges[1]}, {photons[0], merges[0]}};
  }
};

class VcmIteration {
 public:
  // With `counters`, the first iteration of a chosen budget: it also counts its work and adds its
  // samples' terms to each budget's second moment. With `merges_where_needed`, merges only on the
  // paths no connection can make (vcm_budget.h). `camera_samples`: each pixel's camera samples an
  // iteration (empty: one each).
  VcmIteration(const LightingScene& scene, const Camera& camera, const VcmOptions& options, VcmTechniques on,
               float radius, bool merges_where_needed, std::span<const std::uint8_t> camera_samples,
               WorkCounters* counters)
      : scene_(scene),
        camera_(camera),
        options_(options),
        on_(on),
        radius_(radius),
        merges_where_needed_(merges_where_needed),
        camera_samples_(camera_samples),
        counters_(counters),
        eye_(camera_vertex(camera)) {}

  int camera_samples_at(size_t pixel) const { return rt::camera_samples_at(camera_samples_, pixel); }

  // The sample `value` of technique `made_by`, its path's densities `path`, weighted.
  Color weighted(std::span<const PathDensity> path, Technique made_by, const VcmTechniques& on, Color value) const {
    return value * vcm_weight(path, made_by, merges_where_needed_ ? techniques_on_path(path, made_by, on) : on);
  }

  // A light subpath: traced (in `scratch`), each vertex seen by the camera splatted, and kept in
  // `out` where a camera vertex may use it: connected to if it is `pixels_own` (subpath j < P, the
  // one pixel j connects to), merged with if it has a vertex in the grid. Else `out` gets it empty.
  void trace_light_path(Rng& rng, bool pixels_own, std::vector<PathVertex>& scratch, LightChunk& out) const {
    scratch.clear();
    if (counters_) ++counters_->light_subpaths;
    if (const std::optional<LightSubpathStart> start = start_light_subpath(scene_, rng, options_.walk.offset)) {
      scratch.push_back(start->origin);
      WalkSettings walk = options_.walk;
      walk.mode = TransportMode::importance;
      random_walk(scene_, start->ray, start->beta, start->pdf_w, walk, rng, scratch);
      if (counters_) counters_->light_vertices += scratch.size() - 1;
    }
    if ((on_.connect && pixels_own) || (on_.merge && has_photon(scratch)))
      out.vertices.insert(out.vertices.end(), scratch.begin(), scratch.end());
    out.begin.push_back(std::uint32_t(out.vertices.size()));
    if (!on_.light_trace) return;
    const std::span<const PathVertex> path = scratch;
    DensityScratch densities_of;
    for (int s = 1; s <= int(path.size()); ++s) {
      const VcmTechniques techniques = techniques_for(on_, s, options_.camera_sampler);
      if (!techniques.light_trace) continue;
      const StrategySample r =
          connect_strategy(scene_, camera_, std::span(&eye_, 1), path, s, 1, nullptr, options_.walk.offset);
      if (counters_) ++counters_->camera_links;
      if (!r.film_point || r.value == Color(0.0f)) continue;
      const std::optional<size_t> pixel = pixel_of(camera_, *r.film_point);
      if (!pixel) continue;
      const auto densities =
          connection_densities(scene_, camera_, std::span(&eye_, 1), path, s, 1, nullptr, densities_of);
      const Technique made_by{Technique::connection, 1};
      out.splats.push_back(Splat{*r.film_point, weighted(densities, made_by, at_pixel(techniques, *pixel), r.value)});
      if (counters_) out.terms.push_back(budget_terms(densities, made_by, techniques, r.value));
    }
  }

  // Whether light vertex v of `path` (v >= 1) goes in the grid: it can merge (not a delta one, a
  // finite throughput) and, where merges are needed only, is not joined to the vertex before it.
  bool is_photon(std::span<const PathVertex> path, size_t v) const {
    return !path[v].delta && is_finite(path[v].beta) &&
           !(merges_where_needed_ && joined(path[v - 1], v == 1, on_.next_event, on_.connect));
  }
  bool has_photon(std::span<const PathVertex> path) const {
    for (size_t v = 1; v < path.size(); ++v)
      if (is_photon(path, v)) return true;
    return false;
  }

  // A camera sample of pixel `pixel` along `ray`, against light subpath `light_path` and the grid of
  // all of them; in the first iteration of a chosen budget, each technique's terms added to `moments`.
  Color camera_sample(const Ray& ray, Sampler& sampler, size_t pixel, std::span<const PathVertex> light_path,
                      const LightSubpaths& all, const PhotonGrid* grid, std::vector<PathVertex>& camera_path,
                      std::span<double> moments) const {
    camera_path.assign(1, eye_);
    WalkSettings walk = options_.walk;
    walk.mode = TransportMode::radiance;
    random_walk(scene_, ray, Color(1.0f), camera_direction_pdf(camera_, ray.direction), walk, sampler, camera_path);
    if (counters_) counters_->camera_vertices += camera_path.size() - 1;
    const OffsetPolicy& offset = options_.walk.offset;
    DensityScratch scratch;
    Color radiance(0.0f);
    const auto weigh = [&](std::span<const PathDensity> densities, Technique made_by, const VcmTechniques& on,
                           Color value) {
      if (counters_) add_budget_moments(budget_terms(densities, made_by, on, value), moments);
      return weighted(densities, made_by, at_pixel(on, pixel), value);
    };
    for (int t = 2; t <= int(camera_path.size()); ++t) {
      const PathVertex& z = camera_path[size_t(t - 1)];
      if (on_.hit_light && z.emitter >= 0) {
        const StrategySample r = connect_strategy(scene_, camera_, camera_path, light_path, 0, t, nullptr, offset);
        if (r.value != Color(0.0f))
          radiance += weigh(connection_densities(scene_, camera_, camera_path, light_path, 0, t, nullptr, scratch),
                            {Technique::connection, t}, techniques_for(on_, t - 1, options_.camera_sampler), r.value);
      }
      if (z.delta) continue;
      if (on_.next_event || on_.connect) {
        const float u_choice = sampler.uniform();
        const std::optional<PathVertex> fresh = sample_light_vertex(scene_, u_choice, sampler.uniform2());
        const int last_s = on_.connect ? std::max(1, int(light_path.size())) : 1;
        for (int s = on_.next_event ? 1 : 2; s <= last_s; ++s) {
          const PathVertex* light_point = s == 1 ? (fresh ? &*fresh : nullptr) : nullptr;
          if (s == 1 && !light_point) continue;
          const StrategySample r =
              connect_strategy(scene_, camera_, camera_path, light_path, s, t, light_point, offset);
          if (counters_) ++(s == 1 ? counters_->light_points : counters_->connections);
          if (r.value == Color(0.0f)) continue;
          radiance += weigh(connection_densities(scene_, camera_, camera_path, light_path, s, t, light_point, scratch),
                            {Technique::connection, t}, on_, r.value);
        }
      }
      // Where merges are needed only, a camera vertex joined to the one before it merges with none.
      // (Their grid holds only the light vertices not joined to theirs.)
      const PathVertex& before = camera_path[size_t(t - 2)];
      if (grid && !(merges_where_needed_ && joined(before, t == 2, on_.light_trace, on_.connect))) {
        grid->for_each_within(z.point(), radius_, [&](const Photon& photon) {
          const auto [y_path, s] = all.vertex(photon.source);
          if (counters_) count_merge(before, t, y_path[size_t(s - 2)], s);
          const Color value = merge_contribution(camera_path, y_path, s, t, on_.eta);
          if (value == Color(0.0f)) return;
          radiance +=
              weigh(merge_densities(camera_, camera_path, y_path, s, t, scratch), {Technique::merge, t}, on_, value);
        });
      }
    }
    return radiance;
  }

  // In the first iteration, whose grid holds every photon: light vertex s (its predecessor
  // `light_before`) for each chosen budget that would put it in the grid.
  void count_photon(const PathVertex& light_before, int s) const {
    for (const bool connect : {false, true})
      if (!joined(light_before, s == 2, on_.next_event, connect)) ++counters_->photons[connect];
  }

 private:
  // The techniques of `on` with the light-tracing samples that land in `pixel` counted per camera
  // sample of it: N_L / (P n_p), so that the weights of every technique for a path through it sum to
  // one (the camera samples' estimate is their mean).
  VcmTechniques at_pixel(VcmTechniques on, size_t pixel) const {
    on.light_paths /= float(camera_samples_at(pixel));
    return on;
  }

  // In the first iteration: the merge of camera vertex t with light vertex s (their predecessors
  // `camera_before`, `light_before`), for each chosen budget that would make it.
  void count_merge(const PathVertex& camera_before, int t, const PathVertex& light_before, int s) const {
    for (const bool connect : {false, true})
      if (!joined(camera_before, t == 2, on_.light_trace, connect) &&
          !joined(light_before, s == 2, on_.next_event, connect))
        ++counters_->merges[connect];
  }

  const LightingScene& scene_;
  const Camera& camera_;
  const VcmOptions& options_;
  VcmTechniques on_;
  float radius_;
  bool merges_where_needed_;
  std::span<const std::uint8_t> camera_samples_;
  WorkCounters* counters_;
  PathVertex eye_;  // the pinhole's vertex, where every camera subpath starts
};

// One iteration's camera samples: pixel p takes camera_samples[p] (one each where it is empty),
// its sampler's points samples_taken[p] onwards, and `this_film[p]` gets their mean.
// `radiance(pixel, k, ray, sampler, scratch)` is the pixel's camera sample k, `scratch` a vertex
// list of the thread's own.
template <class Radiance>
void camera_pass(const Camera& camera, const RenderSettings& settings, SamplerKind sampler,
                 std::span<const std::uint8_t> camera_samples, int threads, std::vector<std::uint32_t>& samples_taken,
                 std::vector<Color>& this_film, const Radiance& radiance) {
  const PixelFilter filter(settings.filter);
  parallel_for_tiles(camera.width, camera.height, threads, [&](const PixelRect& tile) {
    std::vector<PathVertex> scratch;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const size_t p = size_t(y) * size_t(camera.width) + size_t(x);
        const int samples = camera_samples_at(camera_samples, p);
        Color sum(0.0f);
        for (int k = 0; k < samples; ++k) {
          const auto sample = [&](const Ray& ray, auto& numbers) { return radiance(p, k, ray, numbers, scratch); };
          const int index = int(samples_taken[p]) + k;
          if (sampler == SamplerKind::sobol)
            add_pixel_samples<SobolSampler>(camera, filter, settings, x, y, index, index + 1, sample, sum);
          else
            add_pixel_samples<Rng>(camera, filter, settings, x, y, index, index + 1, sample, sum);
        }
        this_film[p] = sum / float(samples);
        samples_taken[p] += std::uint32_t(samples);
      }
  });
}

}  // namespace

SampleSums render_vcm(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                      const VcmOptions& options, int threads, SampleGuard& guard, ProgressBar* progress,
                      VcmChoice* choice) {
  const int width = camera.width, height = camera.height;
  const size_t pixels = size_t(width) * size_t(height);
  const float initial_radius =
      options.initial_radius > 0.0f ? options.initial_radius : default_merge_radius(scene, camera);
  std::vector<LightChunk> chunk;
  std::vector<Color> film(pixels, Color(0.0f));     // each pixel's camera samples' mean, summed over the iterations
  std::vector<DVec3> splatted(pixels, DVec3(0.0));  // the splats landing in it, summed
  std::vector<Color> this_film(pixels);
  std::vector<DVec3> this_splatted(pixels);
  std::vector<Photon> photons;  // each iteration's, and their grid: kept, their memory reused
  PhotonGrid grid;
  // Every technique and one light subpath per pixel; in --mode vcm the first iteration also measures
  // what each budget would cost and how noisy it would be, and the rest (if any) run the cheapest.
  const bool choose = !options.budget && options.mode == VcmMode::vcm && settings.spp > 1;
  VcmChoice chosen;
  if (options.mode == VcmMode::vcm && options.budget) chosen.budget = *options.budget;
  VcmBudget& budget = chosen.budget;
  WorkCounters counters;
  std::vector<double> pixel_moments;  // the first iteration's, kPixelMoments per pixel
  // Each pixel's camera samples so far: the index of its next sampler point.
  std::vector<std::uint32_t> samples_taken(pixels, 0);
  std::uint32_t iterations = 0;
  for (int i = 0; i < settings.spp && !interrupt_requested(); ++i) {
    const bool first = choose && i == 0;
    if (first) pixel_moments.assign(pixels * kPixelMoments, 0.0);
    std::fill(this_splatted.begin(), this_splatted.end(), DVec3(0.0));
    if (budget.light_paths == 0) {
      // Each camera subpath, with next-event estimation and the light it hits weighed by the power
      // heuristic, is stage 5's path tracer, which takes it without recording its vertices.
      const PathOptions path{.integrator = PathIntegrator::mis,
                             .roulette_start = options.walk.roulette_start,
                             .max_bounces = kMaxSubpathVertices - 2,
                             .offset = options.walk.offset};
      camera_pass(camera, settings, options.camera_sampler, chosen.camera_samples, threads, samples_taken, this_film,
                  [&](size_t, int, const Ray& ray, auto& numbers, std::vector<PathVertex>&) {
                    return guard(path_radiance(scene, ray, path, numbers));
                  });
      if (interrupt_requested()) break;
    } else {
      const float radius = merge_radius(initial_radius, i + 1, options.alpha);
      VcmTechniques on = techniques_of(options.mode);
      on.eta = float(double(pixels) * double(kPi) * double(radius) * double(radius));
      on = techniques_within(on, budget);
      const size_t light_paths = pixels * size_t(budget.light_paths);
      const int chunks = int((light_paths + kLightPathsPerChunk - 1) / kLightPathsPerChunk);
      if (chunk.size() < size_t(chunks)) chunk.resize(size_t(chunks));
      const std::span<LightChunk> used = std::span(chunk).first(size_t(chunks));
      const VcmIteration iteration(scene, camera, options, on, radius, budget.merge == Merging::where_needed,
                                   chosen.camera_samples, first ? &counters : nullptr);

      // The light subpaths, chunk by chunk, then in one list in chunk order. Subpath j of
      // iteration i draws from stream i N_L + j: no two subpaths of a render share one, also when
      // the first iteration's N_L differs from the rest's. Subpath k P + p is the partner of pixel
      // p's camera sample k (and, where the pixel takes more camera samples than there are light
      // subpaths a pixel, of sample k + N_L / P, ...).
      parallel_for(chunks, threads, [&](int c) {
        LightChunk& out = used[size_t(c)];
        out.vertices.clear();
        out.begin.assign(1, 0);
        out.splats.clear();
        out.terms.clear();
        std::vector<PathVertex> scratch;
        const size_t begin = size_t(c) * kLightPathsPerChunk, end = std::min(light_paths, begin + kLightPathsPerChunk);
        for (size_t j = begin; j < end && !interrupt_requested(); ++j) {
          Rng rng(settings.seed, kLightStream, std::uint64_t(i) * light_paths + j);
          iteration.trace_light_path(rng, j / pixels < size_t(iteration.camera_samples_at(j % pixels)), scratch, out);
        }
      });
      if (interrupt_requested()) break;
      const LightSubpaths all{std::span<const LightChunk>(used)};
      if (on.merge) {
        all.photons(photons, [&](std::span<const PathVertex> path, size_t v) {
          const bool photon = iteration.is_photon(path, v);
          if (photon && first) iteration.count_photon(path[v - 1], int(v) + 1);
          return photon;
        });
        grid.assign(std::span(&photons, 1), 2.0f * radius);
      }

      // The camera subpaths, n_p per pixel p, each against its own light subpath and the grid.
      if (on.hit_light || on.connect || on.merge) {
        camera_pass(camera, settings, options.camera_sampler, chosen.camera_samples, threads, samples_taken, this_film,
                    [&](size_t p, int k, const Ray& ray, Sampler& numbers, std::vector<PathVertex>& camera_path) {
                      const std::span<double> moments =
                          first ? std::span(pixel_moments).subspan(p * kPixelMoments, kPixelMoments)
                                : std::span<double>{};
                      const std::span<const PathVertex> partner = all.path(size_t(k % budget.light_paths) * pixels + p);
                      return guard(iteration.camera_sample(ray, numbers, p, partner, all, on.merge ? &grid : nullptr,
                                                           camera_path, moments));
                    });
      } else {
        std::fill(this_film.begin(), this_film.end(), Color(0.0f));
      }
      if (interrupt_requested()) break;
      // Pixel j's light-tracing estimate is its splats' sum over the N_L / P light subpaths per
      // pixel (camera_importance.h): each iteration's splats count P / N_L times. In the first
      // iteration their terms go to their pixels' second moments, in chunk order, so that the sums
      // do not depend on the thread count. (A light subpath keeps only splats that land in a pixel.)
      for (const LightChunk& c : used)
        for (size_t j = 0; j < c.splats.size(); ++j) {
          const size_t p = *pixel_of(camera, c.splats[j].film_point);
          this_splatted[p] += DVec3(guard(c.splats[j].value)) / double(budget.light_paths);
          if (first) add_budget_moments(c.terms[j], std::span(pixel_moments).subspan(p * kPixelMoments, kPixelMoments));
        }
      if (first) {
        // Each budget's plan, and the best.
        chosen = choose_budget(pixel_moments, counters.work(), options.max_light_paths);
        pixel_moments = {};
      }
    }
    for (size_t p = 0; p < pixels; ++p) {
      film[p] += this_film[p];
      splatted[p] += this_splatted[p];
    }
    ++iterations;
    if (progress) progress->advance(pixels);
  }
  if (choice) *choice = chosen;
  SampleSums sums(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(y) * size_t(width) + size_t(x);
      if (iterations > 0) sums.set(x, y, film[p] + Color(splatted[p]), iterations);
    }
  return sums;
}

}  // namespace rt
