// Monte Carlo estimates over an emitter's samples, shared by the stage-4 emitter tests: a mean
// with its standard error, and the one-sample estimate of the projected solid angle, which
// Lambert's polygon formula and the configuration factors of closed_form.h give exactly.
#pragma once

#include "04-radiometry/emitters.h"
#include "common/random.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rt::testing {

// E[g(sample)] over `samples` draws of one generator seeded by `seed`, with its standard error.
struct Mean {
  double value = 0.0, standard_error = 0.0;
};
template <class G>
Mean mean_of(int samples, std::uint64_t seed, G&& g) {
  Rng rng(seed, 0, 0);
  double sum = 0.0, sum2 = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double v = g(rng);
    sum += v;
    sum2 += v * v;
  }
  const double m = sum / samples;
  return {m, std::sqrt(std::max(0.0, sum2 / samples - m * m) / samples)};
}

// cos(theta_x) / p(w) for one sample that x sees from the emitter's front (0 otherwise, and for
// no sample at all): its mean is the projected solid angle, E / L.
inline double projected_solid_angle_sample(const AreaEmitter& e, Vec3 x, Vec3 n, Vec2 u) {
  const EmitterSample s = e.sample(x, u);
  if (!(s.pdf > 0.0f) || e.radiance_towards(s.point, x) == Color(0.0f)) return 0.0;
  return std::max(0.0f, glm::dot(n, s.wi)) / s.pdf;
}

}  // namespace rt::testing
