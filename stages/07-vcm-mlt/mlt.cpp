#include "07-vcm-mlt/mlt.h"

#include "01-ray-casting/camera_rays.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "common/interrupt.h"
#include "common/parallel.h"
#include "common/task.h"

#include <algorithm>

namespace rt {

namespace {

// Without Russian roulette: a multiplexed state's subpaths have exactly the vertices its strategy
// asks for, or it contributes nothing.
WalkSettings exact_walk(const OffsetPolicy& offset, int vertices, TransportMode mode) {
  WalkSettings walk;
  walk.offset = offset;
  walk.max_vertices = vertices;
  walk.roulette_start = kMaxSubpathVertices;
  walk.mode = mode;
  return walk;
}

Vec2 film_point(const Camera& camera, Vec2 u) { return u * Vec2(float(camera.width), float(camera.height)); }

}  // namespace

MltSample multiplexed_sample(const LightingScene& scene, const Camera& camera, const OffsetPolicy& offset, int depth,
                             PrimarySampleSpace& sampler, MltScratch& scratch) {
  MltSample out;
  Sampler& numbers = sampler;
  sampler.start_stream(PrimarySampleSpace::camera);
  // The strategy (s, t) of a path of depth + 2 vertices, from the state's first number.
  const int strategies = depth + 2;
  const int s = std::min(int(sampler.uniform() * float(strategies)), strategies - 1), t = strategies - s;
  const Vec2 film = film_point(camera, sampler.uniform2());
  const Ray ray = generate_camera_ray(camera, film);
  scratch.camera_path.assign(1, camera_vertex(camera));
  random_walk(scene, ray, Color(1.0f), camera_direction_pdf(camera, ray.direction),
              exact_walk(offset, t, TransportMode::radiance), numbers, scratch.camera_path);
  if (int(scratch.camera_path.size()) != t) return out;
  sampler.start_stream(PrimarySampleSpace::light);
  scratch.light_path.clear();
  const bool fresh_light_point = s == 1 && t >= 2;  // next-event estimation samples its own point
  if (s > 0 && !fresh_light_point) {
    const std::optional<LightSubpathStart> start = start_light_subpath(scene, numbers, offset);
    if (!start) return out;
    scratch.light_path.push_back(start->origin);
    random_walk(scene, start->ray, start->beta, start->pdf_w, exact_walk(offset, s, TransportMode::importance), numbers,
                scratch.light_path);
    if (int(scratch.light_path.size()) != s) return out;
  }
  sampler.start_stream(PrimarySampleSpace::connection);
  std::optional<PathVertex> fresh;
  if (fresh_light_point) {
    const float u_choice = sampler.uniform();
    fresh = sample_light_vertex(scene, u_choice, sampler.uniform2());
    if (!fresh) return out;
  }
  const PathVertex* light_point = fresh ? &*fresh : nullptr;
  const StrategySample r =
      connect_strategy(scene, camera, scratch.camera_path, scratch.light_path, s, t, light_point, offset);
  if (r.value == Color(0.0f)) return out;
  const float w = mis_weight(scene, camera, scratch.camera_path, scratch.light_path, s, t, light_point);
  const Color value = r.value * (w * float(strategies));
  out.splats.push_back(Splat{t == 1 ? *r.film_point : film, value});
  out.importance = luminance(value);
  return out;
}

MltSample pssmlt_sample(const LightingScene& scene, const Camera& camera, const MltOptions& options,
                        PrimarySampleSpace& sampler, MltScratch& scratch) {
  MltSample out;
  Sampler& numbers = sampler;
  sampler.start_stream(PrimarySampleSpace::camera);
  const Vec2 film = film_point(camera, sampler.uniform2());
  BdptOptions bdpt;
  bdpt.walk.offset = options.offset;
  bdpt.walk.roulette_start = options.roulette_start;
  scratch.splats.clear();
  const Color own = bdpt_sample(scene, camera, generate_camera_ray(camera, film), bdpt, numbers, scratch.camera_path,
                                scratch.light_path, scratch.splats);
  if (own != Color(0.0f)) out.splats.push_back(Splat{film, own});
  out.splats.insert(out.splats.end(), scratch.splats.begin(), scratch.splats.end());
  for (const Splat& splat : out.splats) out.importance += luminance(splat.value);
  return out;
}

float acceptance(float current, float proposed) {
  // BEGIN TASK stage7.mlt.accept
  return current > 0.0f ? std::min(1.0f, proposed / current) : 1.0f;
  // PLACEHOLDER
  // report_unfinished_task("stage7.mlt.accept");
  // (void)current, (void)proposed;
  // return 1.0f;  // every proposal accepted: independent samples, but weighed as a chain's
  // END TASK
}

ChainStatistics run_chain(PrimarySampleSpace& sampler, Rng& choice, std::int64_t mutations,
                          const std::function<MltSample(PrimarySampleSpace&)>& sample,
                          const std::function<void(const Splat&, float)>& record,
                          const std::function<void(const MltSample&)>& visit) {
  ChainStatistics stats;
  MltSample current = sample(sampler);
  for (std::int64_t m = 0; m < mutations; ++m) {
    if (m % 256 == 255 && interrupt_requested()) break;  // a shorter chain is a chain: it is kept
    sampler.start_iteration();
    MltSample proposed = sample(sampler);
    if (sampler.large_step()) {
      ++stats.large_steps;
      stats.large_step_sum += proposed.importance;
      stats.large_step_sum2 += double(proposed.importance) * proposed.importance;
    }
    const float a = acceptance(current.importance, proposed.importance);
    // Both states, each with its expected weight (Veach's thesis, section 11.4.2).
    if (a > 0.0f && proposed.importance > 0.0f)
      for (const Splat& splat : proposed.splats) record(splat, a / proposed.importance);
    if (a < 1.0f && current.importance > 0.0f)
      for (const Splat& splat : current.splats) record(splat, (1.0f - a) / current.importance);
    ++stats.proposals;
    if (choice.uniform() < a) {
      current = std::move(proposed);
      sampler.accept();
      ++stats.accepted;
    } else {
      sampler.reject();
    }
    if (visit) visit(current);
  }
  return stats;
}

namespace {

// Streams of the chains' own decisions and of their start's choice (Rng's "pixel" argument): far
// above any pixel and apart from the states' (primary_sample_space.cpp).
constexpr std::uint64_t kChainChoiceStreams = std::uint64_t(3) << 61;
constexpr std::uint64_t kChainStartStream = ~std::uint64_t(1);
// Bootstrap samples per unit of parallel work, and chains whose splats are kept apart at once:
// fixed, so nothing depends on the thread count.
constexpr int kBootstrapPerChunk = 1024;
constexpr int kChainsPerGroup = 16;

}  // namespace

SampleSums render_mlt(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                      const MltOptions& options, int threads, SampleGuard& guard, ProgressBar* progress,
                      MltReport* report) {
  const int width = camera.width, height = camera.height;
  const std::int64_t pixels = std::int64_t(width) * height;
  const int states = options.multiplexed ? options.max_depth + 1 : 1;  // depths, or PSSMLT's one
  const auto sample_state = [&](int state, PrimarySampleSpace& sampler, MltScratch& scratch) {
    MltSample s = options.multiplexed ? multiplexed_sample(scene, camera, options.offset, state, sampler, scratch)
                                      : pssmlt_sample(scene, camera, options, sampler, scratch);
    s.importance = 0.0f;
    for (Splat& splat : s.splats) {
      splat.value = guard(splat.value);  // NaN, infinite or negative: black, and counted
      s.importance += luminance(splat.value);
    }
    return s;
  };

  // The bootstrap: independent samples of every state, sample i of state d drawn by the state
  // index d * bootstrap + i, which a chain started from it draws again.
  const std::int64_t bootstrap = std::max(options.bootstrap, 1);
  std::vector<float> weight(size_t(bootstrap * states));
  const int chunks = int((std::int64_t(weight.size()) + kBootstrapPerChunk - 1) / kBootstrapPerChunk);
  parallel_for(chunks, threads, [&](int c) {
    MltScratch scratch;
    const size_t first = size_t(c) * kBootstrapPerChunk, last = std::min(weight.size(), first + kBootstrapPerChunk);
    for (size_t i = first; i < last && !interrupt_requested(); ++i) {
      PrimarySampleSpace sampler(settings.seed, i, options.sigma, options.large_step);
      weight[i] = sample_state(int(i / size_t(bootstrap)), sampler, scratch).importance;
    }
  });
  // Per state, the independent samples of I: the bootstrap's now, the chains' large steps later.
  struct Independent {
    double sum = 0.0, sum2 = 0.0;
    std::int64_t count = 0;
  };
  std::vector<Independent> independent(static_cast<size_t>(states));
  for (size_t i = 0; i < weight.size(); ++i) {
    Independent& d = independent[i / size_t(bootstrap)];
    d.sum += weight[i];
    d.sum2 += double(weight[i]) * weight[i];
    ++d.count;
  }
  std::vector<double> cumulative(weight.size());
  double running = 0.0;
  for (size_t i = 0; i < weight.size(); ++i) cumulative[i] = running += weight[i];

  std::vector<DVec3> film(size_t(pixels), DVec3(0.0));
  std::vector<std::uint32_t> visits(size_t(pixels), 0);
  const std::int64_t total = std::int64_t(options.mutations_per_pixel) * pixels;
  const int chains = std::max(options.chains, 1);
  // The steps of chain c: the total shared as evenly as whole steps allow.
  const auto steps_of = [&](int c) { return total / chains + (c < total % chains ? 1 : 0); };
  std::int64_t done = 0, accepted = 0;
  const auto pixel_of = [&](Vec2 p) {
    const int x = std::clamp(int(p.x), 0, width - 1), y = std::clamp(int(p.y), 0, height - 1);
    return size_t(y) * size_t(width) + size_t(x);
  };
  if (running > 0.0 && !interrupt_requested()) {
    struct ChainOutput {
      std::vector<Splat> splats;
      std::vector<std::uint32_t> visited;
      ChainStatistics stats;
    };
    std::vector<ChainOutput> group(kChainsPerGroup);
    std::vector<int> state_of(kChainsPerGroup);  // the state (depth) of each chain of the group
    for (int first = 0; first < chains && !interrupt_requested(); first += kChainsPerGroup) {
      const int count = std::min(kChainsPerGroup, chains - first);
      parallel_for(count, threads, [&](int k) {
        const int c = first + k;
        ChainOutput& out = group[size_t(k)];
        out = ChainOutput{};
        // The start: a bootstrap sample drawn in proportion to its I.
        Rng start(settings.seed, kChainStartStream, std::uint64_t(c));
        const double target = double(start.uniform()) * running;
        const size_t index =
            std::min(size_t(std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin()),
                     weight.size() - 1);
        PrimarySampleSpace sampler(settings.seed, index, options.sigma, options.large_step);
        Rng choice(settings.seed, kChainChoiceStreams + std::uint64_t(c), 0);
        const int state = int(index / size_t(bootstrap));
        state_of[size_t(k)] = state;
        MltScratch scratch;
        const std::int64_t mutations = steps_of(c);
        out.stats = run_chain(
            sampler, choice, mutations, [&](PrimarySampleSpace& s) { return sample_state(state, s, scratch); },
            [&](const Splat& splat, float w) {
              out.splats.push_back(Splat{splat.film_point, splat.value * w});
            },
            [&](const MltSample& current) {
              if (!current.splats.empty()) out.visited.push_back(std::uint32_t(pixel_of(current.splats[0].film_point)));
            });
      });
      // After a stop request too: each chain of the group ran fewer steps, and counts those.
      for (int k = 0; k < count; ++k) {
        const ChainOutput& out = group[size_t(k)];
        for (const Splat& splat : out.splats) film[pixel_of(splat.film_point)] += DVec3(splat.value);
        for (const std::uint32_t p : out.visited) ++visits[p];
        done += out.stats.proposals;
        accepted += out.stats.accepted;
        Independent& d = independent[size_t(state_of[size_t(k)])];
        d.sum += out.stats.large_step_sum;
        d.sum2 += out.stats.large_step_sum2;
        d.count += out.stats.large_steps;
      }
      std::int64_t planned = 0;
      for (int k = 0; k < count; ++k) planned += steps_of(first + k);
      if (progress) progress->advance(std::uint64_t(planned));
    }
  }
  // b = the sum over the states of their samples' mean I, with its standard error.
  double b = 0.0, variance = 0.0;
  for (const Independent& d : independent) {
    const double n = double(std::max<std::int64_t>(d.count, 1)), mean = d.sum / n;
    b += mean;
    if (d.count > 1) variance += std::max(0.0, d.sum2 / n - mean * mean) / (n - 1.0);
  }
  // Pixel j is b times its splats' sum over the steps per pixel (the chains' splats count each
  // pixel's share of b).
  SampleSums sums(width, height);
  const double scale = done > 0 ? b * double(pixels) / double(done) : 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) sums.set(x, y, Color(film[size_t(y) * size_t(width) + size_t(x)] * scale), 1);
  if (report) *report = MltReport{b, std::sqrt(variance), done, accepted, std::move(visits)};
  return sums;
}

}  // namespace rt
