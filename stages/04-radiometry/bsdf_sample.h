// Stage 4: what BSDF sampling takes and returns (the contract is written out in 04-radiometry/bsdf.h).
#pragma once

#include "common/math.h"

namespace rt {

// What a path carries (Veach's thesis, chapter 5; pbrt's TransportMode): radiance, traced from the
// camera, or importance, traced from the lights (light tracing, BDPT's and photon mapping's light
// subpaths). A light path samples the adjoint BSDF f*(wo, wi) = f(wi, wo), which is f itself
// wherever f is symmetric. It is not symmetric across a refraction: radiance is squeezed by
// (eta_t / eta_i)^2 into the denser side's narrower cone, and importance, like flux, is not
// (DielectricBsdf). Shading normals break the symmetry too, a factor of the shading frame and not of
// the model (ShadingPoint::sample).
enum class TransportMode { radiance, importance };

struct BsdfSample {
  Vec3 wi;       // local frame, pointing away from the surface (below it for a transmitted ray)
  Color weight;  // f cos(theta_i) / pdf; for a delta lobe, its reflectance or transmittance / pdf
  float pdf;     // per unit solid angle; for a delta lobe, the probability of picking it
  bool delta;    // whether wi came from a delta lobe (then pdf is a probability, not a density)
};

}  // namespace rt
