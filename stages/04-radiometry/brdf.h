// Stage 4: the BRDF, f_r(wi -> wo) in sr^-1, the ratio of radiance reflected towards wo to the
// irradiance arriving from wi (Nicodemus et al., "Geometrical Considerations and Nomenclature for
// Reflectance", NBS 1977). The reflection equation it serves:
//     L_r(x, wo) = integral over the hemisphere of f_r(wi -> wo) L_i(x, wi) cos(theta_i) dwi.
//
// THE CONTRACT every model below keeps (tests/stage4/brdf_test.cpp checks each point):
//  - Directions are unit vectors in the local shading frame (normal = +z), both pointing AWAY from
//    the surface: wo towards the viewer, wi towards the light.
//  - eval(wi, wo) returns f_r. It is 0 for delta lobes (their f_r is a Dirac delta, which no
//    direction chosen independently can meet) and 0 when wi and wo are not both above the surface.
//  - sample(wo, u) draws wi and returns it with
//      pdf:    the density of wi per unit SOLID ANGLE, equal to pdf(wi, wo); for a delta lobe, the
//              discrete probability of having picked that lobe;
//      weight: f_r(wi -> wo) cos(theta_i) / pdf, the factor an estimator multiplies L_i(wi) by;
//              for a delta lobe, the lobe's reflectance over the probability of picking it.
//    or nothing when the sample is wasted (e.g. a glossy lobe's wi below the surface).
//  - pdf(wi, wo) is the solid-angle density sample() draws wi with, 0 for delta lobes. Over the
//    sphere it integrates to 1 minus the probability that sample() returns nothing.
//  - Reciprocity, f_r(wi -> wo) = f_r(wo -> wi), and energy conservation, the directional albedo
//    integral f_r cos(theta_i) dwi <= 1 for every wo, hold for every model.
#pragma once

#include "04-radiometry/lambert.h"
#include "04-radiometry/microfacet.h"
#include "04-radiometry/phong.h"
#include "04-radiometry/specular.h"
#include "common/hit.h"
#include "common/scene.h"

#include <optional>
#include <variant>

namespace rt {

// One BRDF model among those of this stage; a value type, so building one per hit costs no
// allocation. Each alternative keeps the contract above.
class Brdf {
 public:
  using Model = std::variant<LambertBrdf, PhongBrdf, MicrofacetBrdf, MirrorBrdf, DielectricBsdf>;

  explicit Brdf(Model model) : model_(model) {}

  Color eval(Vec3 wi, Vec3 wo) const {
    return std::visit([&](const auto& m) { return m.eval(wi, wo); }, model_);
  }
  std::optional<BrdfSample> sample(Vec3 wo, Vec2 u, float u_lobe) const {
    return std::visit([&](const auto& m) { return m.sample(wo, u, u_lobe); }, model_);
  }
  float pdf(Vec3 wi, Vec3 wo) const {
    return std::visit([&](const auto& m) { return m.pdf(wi, wo); }, model_);
  }
  // Whether every direction it reflects into is a delta lobe (mirror, glass).
  bool is_delta() const {
    return std::holds_alternative<MirrorBrdf>(model_) || std::holds_alternative<DielectricBsdf>(model_);
  }
  const Model& model() const { return model_; }

 private:
  Model model_;
};

// The BRDF of `material` at a hit: the diffuse albedo is read at the hit point (checker), and
// glass learns from the hit's face which side it is entered from. Stage 1's empirical
// Blinn-Phong highlight of a `diffuse` material is not energy conserving, so a diffuse material is
// pure Lambert here; glossy surfaces use the `phong` or `microfacet` types.
Brdf make_brdf(const Material& material, const Hit& hit);

}  // namespace rt
