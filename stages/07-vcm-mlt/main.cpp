// stage7: renders a scene by vertex connection and merging, by one of the methods it contains
// (--mode bpt, ppm, lt), or by Metropolis light transport (--mode mlt, pssmlt).
#include "01-ray-casting/render.h"
#include "06-light-transport/transport_render.h"
#include "07-vcm-mlt/mlt.h"
#include "07-vcm-mlt/vcm.h"
#include "common/error.h"
#include "common/heat_map.h"
#include "common/image_io.h"
#include "common/sample_batch.h"
#include "common/stage_program.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace {

enum class Mode { vcm, bpt, ppm, lt, mlt, pssmlt };
const std::pair<const char*, Mode> kModes[] = {{"vcm", Mode::vcm}, {"bpt", Mode::bpt}, {"ppm", Mode::ppm},
                                               {"lt", Mode::lt},   {"mlt", Mode::mlt}, {"pssmlt", Mode::pssmlt}};
const char* name_of(Mode mode) {
  for (const auto& [name, m] : kModes)
    if (m == mode) return name;
  return "?";
}

// The first iteration's estimates, each budget's second moment times cost (what its error squared
// times its time would be) relative to the chosen one's.
void print_choice(const rt::VcmChoice& choice) {
  using namespace rt;
  const VcmWork& w = choice.work;
  std::printf(
      "stage7: the first iteration's work: %llu camera vertices, %llu light points, %llu light subpaths, "
      "%llu light vertices, %llu camera links, %llu connections; "
      "with connections %llu photons and %llu merges, without %llu and %llu\n",
      static_cast<unsigned long long>(w.camera_vertices), static_cast<unsigned long long>(w.light_points),
      static_cast<unsigned long long>(w.light_subpaths), static_cast<unsigned long long>(w.light_vertices),
      static_cast<unsigned long long>(w.camera_links), static_cast<unsigned long long>(w.connections),
      static_cast<unsigned long long>(w.with_connections.photons),
      static_cast<unsigned long long>(w.with_connections.merges),
      static_cast<unsigned long long>(w.without_connections.photons),
      static_cast<unsigned long long>(w.without_connections.merges));
  std::printf("stage7: the first iteration's estimates of error^2 x time, relative to the chosen budget:\n");
  size_t chosen = 0;
  for (size_t b = 0; b < kVcmBudgetCount; ++b)
    if (kVcmBudgets[b] == choice.budget) chosen = b;
  const double best = choice.plans[chosen].product();
  for (size_t b = 0; b < kVcmBudgetCount; ++b) {
    const double relative = choice.plans[b].product() / best;
    std::printf("  %-78s %s%s\n", describe(kVcmBudgets[b]).c_str(),
                std::isfinite(relative) ? std::to_string(relative).substr(0, 6).c_str() : "misses light",
                b == chosen ? "  <- chosen" : "");
  }
  // How many pixels take each count of camera samples in the chosen budget's plan.
  std::array<std::size_t, kCameraSampleChoices> pixels{};
  for (const std::uint8_t n : choice.camera_samples)
    for (size_t c = 0; c < kCameraSampleChoices; ++c)
      if (n == kCameraSampleCounts[c]) ++pixels[c];
  if (!choice.camera_samples.empty()) {
    std::printf("stage7: camera samples a pixel per iteration:");
    for (size_t c = 0; c < kCameraSampleChoices; ++c)
      std::printf(" %d in %zu pixels%s", kCameraSampleCounts[c], pixels[c], c + 1 < kCameraSampleChoices ? "," : "\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  Mode mode = Mode::vcm;
  VcmOptions vcm;
  MltOptions mlt;
  std::optional<float> radius, alpha;
  int mutations = 0, chains = 0, bootstrap = 0;  // 0: not given
  std::optional<float> large_step;
  std::optional<SamplerKind> sampler;
  std::string mutation_map;
  std::string budget;  // empty: not given

  return run_stage_program(
      argc, argv, "stage7", "Stage 7: vertex connection and merging, and Metropolis light transport", options,
      [&](StageFlags& flags) {
        std::vector<std::pair<std::string, Mode>> modes;
        for (const auto& [name, m] : kModes) modes.emplace_back(name, m);
        flags.add_choice("--mode", mode, modes,
                         "vcm (connections and merges, the default), bpt (connections only: bidirectional path "
                         "tracing), ppm (merges only: progressive photon mapping), lt (light tracing), mlt "
                         "(multiplexed Metropolis light transport over BDPT's strategies) or pssmlt (Kelemen's "
                         "Metropolis over whole BDPT samples); for vcm, bpt, ppm and lt --spp is the number of "
                         "iterations, each one light subpath and one camera subpath per pixel");
        flags.add("--radius", radius,
                  "vcm, ppm: the first iteration's merge radius in scene units (default: one pixel footprint at "
                  "the median distance of what the camera sees)",
                  finite_in(1e-30, 1e30));
        flags.add("--alpha", alpha,
                  "vcm, ppm: the radius shrinks as r_i = r_1 i^((alpha - 1) / 2), alpha in (0, 1] (default 0.75)",
                  finite_in(1e-6, 1.0));
        flags.add_choice("--sampler", sampler, sampler_words(),
                         "vcm, bpt, ppm: the camera subpaths' numbers, independent (as stage6's BDPT draws them) or "
                         "sobol (stage 5's scrambled Sobol points, one per iteration: the default)");
        std::vector<std::string> budget_words{"auto"};
        for (const VcmBudget& b : kVcmBudgets) budget_words.push_back(budget_word(b));
        budget_words.push_back(budget_word(kEveryTechnique));
        flags.add_word("--budget", budget, budget_words,
                       "vcm: auto (the default): the first iteration runs every technique and estimates which "
                       "budget the rest should run, and how many camera samples (1, 2, 4, 8) each pixel takes per "
                       "iteration, for the least error in their time; a budget given takes one a pixel; all: every "
                       "iteration runs "
                       "every technique, one light subpath per pixel, merges everywhere, as Georgiev et al. "
                       "publish it; pt: no light subpaths (path tracing); 1, 8: that many light subpaths per "
                       "pixel, c: with connections, m: with merges where only they reach (1cm, 8m, ...)");
        flags.add("--mutations-per-pixel", mutations,
                  "mlt, pssmlt: the chains' steps in all, per pixel (default 100; replaces --spp)",
                  decimal_in(1, 1000000));
        flags.add("--large-step", large_step, "mlt, pssmlt: the probability of a large step (default 0.3)",
                  finite_in(0.0, 1.0));
        flags.add("--chains", chains, "mlt, pssmlt: independent Markov chains (default 1024)", decimal_in(1, 1000000));
        flags.add("--bootstrap", bootstrap,
                  "mlt, pssmlt: independent samples estimating the image's brightness and the chains' starts "
                  "(per path depth for mlt; default 100000)",
                  decimal_in(1, 100000000));
        flags.add_max_depth(options, "mlt: the deepest path a chain may take, in bounces");
        flags.add_output("--mutation-map", mutation_map,
                         "mlt, pssmlt: also write a PNG heat map of where the chains spent their steps, on a log "
                         "scale (black: none, pale yellow: the most any pixel got)");
        flags.add("--roulette-start", vcm.walk.roulette_start,
                  "Bounces before Russian roulette may end a subpath (default 4; not mlt, whose subpaths have the "
                  "length their strategy asks for)",
                  decimal_in(0, 1000));
      },
      [&] {
        const bool metropolis = mode == Mode::mlt || mode == Mode::pssmlt;
        const std::string what = std::string("--mode ") + name_of(mode);
        const auto refuse = [&](bool given, const char* flag, const char* whose) {
          if (given) throw UsageError(std::string(flag) + " is for " + whose + ", not " + what);
        };
        refuse((radius || alpha) && mode != Mode::vcm && mode != Mode::ppm, radius ? "--radius" : "--alpha",
               "--mode vcm and ppm");
        refuse(!metropolis && (mutations || large_step || chains || bootstrap),
               mutations    ? "--mutations-per-pixel"
               : large_step ? "--large-step"
               : chains     ? "--chains"
                            : "--bootstrap",
               "--mode mlt and pssmlt");
        refuse(sampler && (metropolis || mode == Mode::lt), "--sampler", "--mode vcm, bpt and ppm");
        refuse(!budget.empty() && mode != Mode::vcm, "--budget", "--mode vcm");
        for (const VcmBudget& b : kVcmBudgets)
          if (budget == budget_word(b)) vcm.budget = b;
        if (budget == "all") vcm.budget = kEveryTechnique;
        refuse(!metropolis && !mutation_map.empty(), "--mutation-map", "--mode mlt and pssmlt");
        if (!mutation_map.empty() && image_format_for(mutation_map) != ImageFormat::png)
          throw UsageError("--mutation-map: the heat map is a picture: give a .png file");
        refuse(mode != Mode::mlt && options.max_depth.has_value(), "--max-depth",
               "--mode mlt (every other mode ends paths by Russian roulette)");
        if (options.sample_range || options.crop || is_batch_path(options.out))
          throw UsageError(what +
                           ": light paths land anywhere on the film, merge radii shrink with every iteration and "
                           "chains wander over the whole image, so it cannot be rendered in batches or windows: "
                           "render it whole (stage5 can)");
        if (radius) vcm.initial_radius = *radius;
        if (alpha) vcm.alpha = *alpha;
        if (sampler) vcm.camera_sampler = *sampler;
        mlt.multiplexed = mode == Mode::mlt;
        if (mutations) mlt.mutations_per_pixel = mutations;
        if (large_step) mlt.large_step = *large_step;
        if (chains) mlt.chains = chains;
        if (bootstrap) mlt.bootstrap = bootstrap;
        mlt.roulette_start = vcm.walk.roulette_start;
        const SceneDescription description = load_scene(options.scene);
        RenderSettings settings = options.settings_for(description);
        if (metropolis) settings.spp = mlt.mutations_per_pixel;  // the progress bar counts steps
        mlt.max_depth = settings.max_depth;
        vcm.max_light_paths = check_vcm_fits(description, settings, memory_limit());
        if (settings.filter != PixelFilterType::box)
          throw UsageError(
              "--filter: stage7 uses the box filter (a splat lands in one pixel); other filters, from "
              "--filter or the scene, need stage5");
        const LightingScene scene(description);
        const Camera camera(description.camera, settings.width, settings.height);
        check_light_paths_renderable(description, scene, camera, what, "stage6 --method pt",
                                     "stage6 --method pt or sppm");
        if (!metropolis) vcm.mode = VcmMode(int(mode));
        if (!metropolis && techniques_of(vcm.mode).merge) {
          if (!(vcm.initial_radius > 0.0f)) vcm.initial_radius = default_merge_radius(scene, camera);
          std::printf("stage7: merge radius %.4g at the first iteration, shrinking as i^%.3g\n", vcm.initial_radius,
                      0.5 * (vcm.alpha - 1.0));
        }
        SampleGuard guard;
        MltReport report;
        VcmChoice chosen;
        render_with_progress_and_write(
            "stage7", options, description, settings, PixelMeaning::radiance, [&](ProgressBar* progress) {
              return metropolis ? render_mlt(scene, camera, settings, mlt, options.threads, guard, progress, &report)
                                : render_vcm(scene, camera, settings, vcm, options.threads, guard, progress, &chosen);
            });
        if (chosen.measured) print_choice(chosen);
        if (metropolis) {
          std::printf("stage7: b = %.4g +- %.2g (bootstrap and large steps), %lld steps, %.1f %% accepted\n", report.b,
                      report.b_standard_error, static_cast<long long>(report.mutations),
                      report.mutations > 0 ? 100.0 * double(report.accepted) / double(report.mutations) : 0.0);
          if (!mutation_map.empty() && !report.visits.empty()) {
            // On a log scale: a chain dwells on the brightest pixels hundreds of times longer than on
            // the rest, which a linear scale shows black.
            std::vector<std::uint32_t> shade(report.visits.size());
            for (size_t i = 0; i < shade.size(); ++i) shade[i] = std::uint32_t(1000.0 * std::log1p(report.visits[i]));
            write_image(mutation_map, heat_map(shade, settings.width, settings.height,
                                               *std::max_element(shade.begin(), shade.end())));
          }
        }
        if (guard.dropped() > 0)
          std::printf("stage7: %llu samples had NaN, infinite or negative radiance and were counted as black\n",
                      static_cast<unsigned long long>(guard.dropped()));
      });
}
