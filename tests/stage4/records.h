// The plain-data forms (tests/support/record.h) of stage 4's results that its graded tests record.
#pragma once

#include "04-radiometry/bsdf_sample.h"
#include "04-radiometry/direct_lighting.h"
#include "04-radiometry/discrete_distribution.h"
#include "04-radiometry/emitters.h"
#include "04-radiometry/environment_light.h"
#include "04-radiometry/piecewise_constant.h"
#include "support/record.h"

namespace rt {

inline auto record_fields(BsdfSample& s) { return std::tie(s.wi, s.weight, s.pdf, s.delta); }
inline auto record_fields(EmitterSample& s) { return std::tie(s.point, s.wi, s.distance, s.pdf); }
inline auto record_fields(EnvironmentSample& s) { return std::tie(s.wi, s.pdf, s.radiance); }
inline auto record_fields(DirectLightSample& s) { return std::tie(s.value, s.wi, s.pdf); }
inline auto record_fields(PiecewiseConstant1D::Sample& s) { return std::tie(s.x, s.pdf, s.bin); }
inline auto record_fields(PiecewiseConstant2D::Sample& s) { return std::tie(s.st, s.pdf); }
inline auto record_fields(DiscreteDistribution::Choice& c) { return std::tie(c.index, c.pmf); }

}  // namespace rt
