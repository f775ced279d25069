// Stage 7: Metropolis light transport in primary sample space (primary_sample_space.h). A Markov
// chain whose states are the numbers a path sampler draws visits them in proportion to a target
// I(u), the luminance of what the sample adds to the image: bright paths are revisited and
// perturbed, so a chain that found the light through a door ajar keeps exploring its neighbours,
// where independent samples would find it again only by chance. Metropolis–Hastings keeps the chain
// at that target: a proposal v from state u is accepted with probability
//     a(u -> v) = min(1, I(v) T(v -> u) / (I(u) T(u -> v))) = min(1, I(v) / I(u))
// (the steps are symmetric), which makes I(u) T(u -> v) a(u -> v) = I(v) T(v -> u) a(v -> u):
// detailed balance, so I is the chain's stationary density (Metropolis et al. 1953; Hastings 1970;
// Veach's thesis, chapter 11). A state's contributions, divided by I, then count each pixel's share
// of the whole image's b = integral of I, which a bootstrap of independent samples estimates.
// Each step records both states with their expected weights, the proposal a / I(v) and the
// current state (1 - a) / I(u), whichever the chain keeps (Veach, section 11.4.2; pbrt-v3's
// MLTIntegrator): less noise than recording only the state kept, and the same expectation.
//
// Two inner samplers, one chain:
//   - Kelemen et al.'s PSSMLT: one state is a whole BDPT sample (stage 6's bdpt_sample), all its
//     strategies and splats;
//   - multiplexed MLT (Hachisuka, Kaplanyan & Dachsbacher, "Multiplexed Metropolis Light
//     Transport", SIGGRAPH 2014): one state is one path depth k, one strategy (s, t) chosen by
//     the state's first number, evaluated alone and weighted by its MIS weight times the k + 2
//     strategies of that depth. The chain then also moves between strategies, to the one that
//     samples the path it found best, and a chain's depth is fixed, drawn by the bootstrap.
#pragma once

#include "05-path-tracing/path_tracer.h"
#include "06-light-transport/bdpt.h"
#include "07-vcm-mlt/primary_sample_space.h"
#include "common/progress.h"
#include "common/sample_sums.h"

#include <functional>

namespace rt {

struct MltOptions {
  bool multiplexed = true;        // false: Kelemen's PSSMLT over whole BDPT samples
  int mutations_per_pixel = 100;  // the chains' proposals in all, per pixel of the image
  float large_step = 0.3f;        // the probability of a large step
  float sigma = 0.01f;            // a small step's deviation per coordinate
  int chains = 1024;              // independent chains, a fixed number whatever the threads
  int bootstrap = 100000;         // independent samples estimating b (per depth, multiplexed)
  int max_depth = 10;             // multiplexed: the path depths 0 ... max_depth (edges minus 1)
  int roulette_start = 4;         // PSSMLT: stage 5's Russian roulette inside BDPT's walks
  OffsetPolicy offset;
};

// What one state adds to the image: its contributions and where they land, and I, the sum of
// their luminances.
struct MltSample {
  std::vector<Splat> splats;
  float importance = 0.0f;
};

// The state's numbers turned into contributions: a multiplexed state of depth k, or (k ignored)
// a PSSMLT state. Scratch space for the subpaths is the caller's.
struct MltScratch {
  std::vector<PathVertex> camera_path, light_path;
  std::vector<Splat> splats;
};
MltSample multiplexed_sample(const LightingScene& scene, const Camera& camera, const OffsetPolicy& offset, int depth,
                             PrimarySampleSpace& sampler, MltScratch& scratch);
MltSample pssmlt_sample(const LightingScene& scene, const Camera& camera, const MltOptions& options,
                        PrimarySampleSpace& sampler, MltScratch& scratch);

// Task stage7.mlt.accept. The Metropolis–Hastings acceptance of a proposal of target `proposed`
// from a state of target `current`, for symmetric steps: min(1, proposed / current); 1 from a state
// of target 0 (a chain that starts on nothing leaves it at once).
float acceptance(float current, float proposed);

// One chain of `mutations` steps from the state `sampler` holds (read once before the first step),
// each proposal made by `sample(sampler)`; calls record(splat, weight) for every contribution of
// both states with its expected weight (a / I(v) for the proposal, (1 - a) / I(u) for the
// current), and, if given, visit(state) with the state the chain is in after each step. `choice`
// draws the chain's own decisions (large or small is the sampler's). A stop request ends it early;
// the statistics count the steps made.
struct ChainStatistics {
  std::int64_t proposals = 0, accepted = 0;
  // The large steps' proposals: independent samples of I, which sharpen the bootstrap's b
  // (Kelemen et al., section 4).
  std::int64_t large_steps = 0;
  double large_step_sum = 0.0, large_step_sum2 = 0.0;
};
ChainStatistics run_chain(PrimarySampleSpace& sampler, Rng& choice, std::int64_t mutations,
                          const std::function<MltSample(PrimarySampleSpace&)>& sample,
                          const std::function<void(const Splat&, float)>& record,
                          const std::function<void(const MltSample&)>& visit = nullptr);

// What a render measured besides its image.
struct MltReport {
  // The estimate of the image's integral of I, from the bootstrap and the large steps, and its
  // standard error.
  double b = 0.0, b_standard_error = 0.0;
  std::int64_t mutations = 0, accepted = 0;
  std::vector<std::uint32_t> visits;  // per pixel, the steps that ended with the chain's state there
};

// The whole render: the bootstrap (options.bootstrap independent samples per depth), then
// options.chains chains of (mutations_per_pixel x pixels) / chains steps, each started from a
// bootstrap sample drawn in proportion to its I (so no chain starts out of the stationary
// distribution: no start-up bias). b is the mean I of every independent sample of each depth: the
// bootstrap's and the chains' large steps'. Per pixel the image, with the count 1. The same bit for bit for
// any thread count: bootstrap sample and chain i draw from their own streams, and the chains'
// splats are added in chain order, a fixed group of chains at a time. A stop request ends every
// chain of the group under way early and starts no other; the image is scaled by the steps made.
SampleSums render_mlt(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                      const MltOptions& options, int threads, SampleGuard& guard, ProgressBar* progress = nullptr,
                      MltReport* report = nullptr);

}  // namespace rt
