// Stage 4: what BSDF sampling returns (the contract is written out in 04-radiometry/bsdf.h).
#pragma once

#include "common/math.h"

namespace rt {

struct BsdfSample {
  Vec3 wi;       // local frame, pointing away from the surface (below it for a transmitted ray)
  Color weight;  // f cos(theta_i) / pdf; for a delta lobe, its reflectance or transmittance / pdf
  float pdf;     // per unit solid angle; for a delta lobe, the probability of picking it
  bool delta;    // whether wi came from a delta lobe (then pdf is a probability, not a density)
};

}  // namespace rt
