// Stage 5: Monte Carlo path tracing. The rendering equation
//     L(x, wo) = Le(x, wo) + integral_H f_r(wo, wi) L(x', -wi) cos(theta_i) dwi,
// written L = E + K L with K the transport operator, has the Neumann series L = sum_k K^k E: light
// that has bounced k times. A path tracer estimates every term at once by following one random
// direction per bounce (N = 1 per bounce keeps the cost of a path linear in its length, where N > 1
// would grow as N^k), multiplying the throughput beta by f_r cos / p at each step.
//
// The lecture's path tracer, step by step, each kept as an integrator to compare:
//  1. naive (--integrator naive): BRDF sampling only, a fixed maximum depth; light is found only
//     when a path happens to hit an emitter.
//  2. russian_roulette (rr): the same without a fixed depth: after a few bounces a path survives
//     with probability P and its throughput is divided by P, which keeps the expectation unchanged
//     (Arvo & Kirk, "Particle Transport and Image Synthesis", SIGGRAPH 1990).
//  3. next_event_estimation (nee): at each non-delta vertex, direct light from a sampled emitter
//     point (stage 4's light estimator, behind a shadow ray), plus the BRDF-sampled bounce for
//     indirect light, which IGNORES the emitters it hits, so no light is counted twice.
//  4. mis (mis): both the light sample and the BRDF sample count emitted light, each weighted by
//     Veach's power heuristic w = p^2 / (p_light^2 + p_brdf^2) (Veach & Guibas, "Optimally
//     Combining Sampling Techniques for Monte Carlo Rendering", SIGGRAPH 1995), which is what
//     glossy surfaces under large lights need.
#pragma once

#include "04-radiometry/direct_lighting.h"
#include "05-path-tracing/sobol_sampler.h"

#include <atomic>
#include <cstdint>

namespace rt {

enum class PathIntegrator { naive, russian_roulette, next_event_estimation, mis };

struct PathOptions {
  PathIntegrator integrator = PathIntegrator::mis;
  int max_depth = 5;       // naive: the number of bounces
  // The others: bounces before roulette may end a path. Every early bounce still carries most of
  // the light in a closed room (albedo ~0.7), so ending paths there adds more variance than it saves
  // time. Measured on the Cornell box (docs/stage5.md, section 3): starting after bounce 4 reaches
  // a given error 1.4 times sooner than after bounce 1; 5 and 6 are no better.
  int roulette_start = 4;
  int max_bounces = 1024;  // a safety cap for roulette paths (survival P <= 0.95 ends them long before)
  OffsetPolicy offset;
};

// Task stage5.path.russian_roulette. The survival probability after a bounce with throughput beta:
// P = min(0.95, max component of beta). Paths carrying little light end early; P < 1 always, so a
// path in a white furnace ends too. The caller divides beta by P when the path survives.
float survival_probability(Color beta);

// Task stage5.path.mis_weight. Veach's power heuristic with beta = 2 for one sample of each of two
// strategies: w_a = p_a^2 / (p_a^2 + p_b^2). Infinite p_a (a delta) gives 1.
float power_heuristic(float pdf_a, float pdf_b);

// The radiance arriving along a camera ray, estimated by one path, with numbers drawn from `sampler`.
// The sampler's type is a template parameter, so that its calls compile into the path loop: a path
// draws five to seven numbers per bounce, and through the Sampler interface each would be a call the
// compiler cannot see into (docs/stage5.md, the speed ladder). Defined in path_tracer.cpp for the
// two samplers and for the interface itself (a caller that holds only a Sampler&).
template <SamplerType S>
Color path_radiance(const LightingScene& scene, const Ray& ray, const PathOptions& options, S& sampler);
extern template Color path_radiance(const LightingScene&, const Ray&, const PathOptions&, Rng&);
extern template Color path_radiance(const LightingScene&, const Ray&, const PathOptions&, SobolSampler&);
extern template Color path_radiance(const LightingScene&, const Ray&, const PathOptions&, Sampler&);

// The solid-angle density with which light sampling (stage 4: emitter by power, point on it) would
// have produced the direction from `from` to the emitter point of `hit`; 0 if `hit` is no emitter.
float light_sampling_pdf(const LightingScene& scene, Vec3 from, const Hit& hit);
// The same for a direction that leaves the scene: the environment's share of the choice times its
// density for `direction`; 0 without an environment.
float environment_sampling_pdf(const LightingScene& scene, Vec3 direction);

// Keeps NaN, Inf and negative radiance out of the image, and counts each such sample instead of
// hiding it: one NaN would otherwise turn a whole pixel (and every average over it) into NaN.
// The count is reported with the image, so a broken BRDF or pdf shows up as a number, not a speck.
class SampleGuard {
 public:
  Color operator()(Color sample) {
    if (is_finite(sample) && min_component(sample) >= 0.0f) return sample;
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return Color(0.0f);
  }
  std::uint64_t dropped() const { return dropped_.load(); }

 private:
  std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace rt
