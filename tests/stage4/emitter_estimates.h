// Monte Carlo estimates over an emitter's samples, shared by the stage-4 emitter tests: a mean
// with its standard error, and the one-sample estimate of the projected solid angle, which
// Lambert's polygon formula and the configuration factors of closed_form.h give exactly.
#pragma once

#include "04-radiometry/emitters.h"
#include "common/random.h"
#include "support/sample_mean.h"
#include "support/subject.h"

#include <algorithm>
#include <cstdint>

namespace rt::testing {

// E[g(sample)] over `samples` draws of one generator seeded by `seed`, with its standard error.
template <class G>
Estimate mean_of(int samples, std::uint64_t seed, G&& g) {
  return subject([&] {
    Rng rng(seed, 0, 0);
    SampleMean m;
    for (int k = 0; k < samples; ++k) m.add(g(rng));
    return m.estimate();
  });
}

// cos(theta_x) / p(w) for one sample that x sees from the emitter's front (0 otherwise, and for
// no sample at all): its mean is the projected solid angle, E / L.
inline double projected_solid_angle_sample(const AreaEmitter& e, Vec3 x, Vec3 n, Vec2 u) {
  const EmitterSample s = e.sample(x, u);
  if (!(s.pdf > 0.0f) || e.radiance_towards(s.point, x) == Color(0.0f)) return 0.0;
  return std::max(0.0f, glm::dot(n, s.wi)) / s.pdf;
}

}  // namespace rt::testing
