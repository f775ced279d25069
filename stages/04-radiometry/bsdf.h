// Stage 4: the BSDF f(wo, wi) in sr^-1, the ratio of radiance scattered towards wo to the
// irradiance arriving from wi (Nicodemus et al., "Geometrical Considerations and Nomenclature for
// Reflectance", NBS 1977): a BRDF where light is reflected, and for glass a BTDF part as well,
// where it is transmitted. The scattering equation it serves:
//     L_o(x, wo) = integral over the sphere of f(wo, wi) L_i(x, wi) |cos(theta_i)| dwi.
//
// THE CONTRACT every model below keeps (tests/stage4/brdf_test.cpp checks each point):
//  - Directions are unit vectors in the local shading frame (normal = +z), both pointing AWAY from
//    the surface: wo towards the viewer (above it, wo.z > 0), wi towards where the light comes from.
//    Every call takes wo first (as pbrt and Nori do).
//  - eval(wo, wi) returns f. It is 0 for delta lobes (their f is a Dirac delta, which no direction
//    chosen independently can meet). The reflecting models (Lambert, Phong, GGX) return 0 unless
//    wi is above the surface too; only glass scatters below it, and only by a delta lobe.
//  - sample(wo, u, u_lobe) draws wi and returns it with
//      pdf:    the density of wi per unit SOLID ANGLE, equal to pdf(wo, wi); for a delta lobe, the
//              discrete probability of having picked that lobe;
//      weight: f(wo, wi) |cos(theta_i)| / pdf, the factor an estimator multiplies L_i(wi) by; for a
//              delta lobe, the lobe's reflectance or transmittance over the probability of picking it;
//      delta:  whether the lobe was a delta;
//    or nothing when the sample is wasted (e.g. a glossy lobe's wi below the surface).
//  - pdf(wo, wi) is the solid-angle density sample() draws wi with, 0 for delta lobes. Over the
//    sphere it integrates to 1 minus the probability that sample() returns nothing.
//  - Reciprocity, f(wo, wi) = f(wi, wo) for reflection, and energy conservation, the directional
//    albedo integral f |cos(theta_i)| dwi <= 1 for every wo, hold for every model.
//  - sample() takes the quantity the path carries (TransportMode), wo being the direction the path
//    arrived from in either mode. Only refraction tells them apart: its weight is
//    (eta_outside / eta_inside)^2 times larger for radiance than for importance.
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

// One scattering model among those of this stage; a value type, so building one per hit costs no
// allocation. Each alternative keeps the contract above.
class Bsdf {
 public:
  using Model = std::variant<LambertBrdf, PhongBrdf, MicrofacetBrdf, MirrorBrdf, DielectricBsdf>;

  explicit Bsdf(Model model) : model_(model) {}

  Color eval(Vec3 wo, Vec3 wi) const {
    return std::visit([&](const auto& m) { return m.eval(wo, wi); }, model_);
  }
  std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, float u_lobe, TransportMode mode = TransportMode::radiance) const {
    return std::visit(
        [&](const auto& m) {
          if constexpr (requires { m.sample(wo, u, u_lobe, mode); })
            return m.sample(wo, u, u_lobe, mode);
          else
            return m.sample(wo, u, u_lobe);  // a symmetric model: the same for either mode
        },
        model_);
  }
  float pdf(Vec3 wo, Vec3 wi) const {
    return std::visit([&](const auto& m) { return m.pdf(wo, wi); }, model_);
  }
  // Whether every direction it reflects into is a delta lobe (mirror, glass).
  bool is_delta() const {
    return std::holds_alternative<MirrorBrdf>(model_) || std::holds_alternative<DielectricBsdf>(model_);
  }
  // Whether sample() reads u_lobe: only a model of two lobes does (Phong's diffuse and glossy
  // parts, glass's reflection and refraction). A caller may skip drawing that number otherwise.
  bool has_lobe_choice() const {
    return std::holds_alternative<PhongBrdf>(model_) || std::holds_alternative<DielectricBsdf>(model_);
  }
  // The model itself, for make_bsdf's tests: they check what it chose without evaluating it, which
  // would make them depend on each model's task.
  const Model& model() const { return model_; }

 private:
  Model model_;
};

// The BSDF of `material` at a hit: the diffuse albedo is read at the hit point (a checker, for
// diffuse and phong alike), and glass learns from the hit's face which side it is entered from.
// Stage 1's empirical Blinn-Phong highlight of a `diffuse` material is not energy conserving, so a
// diffuse material is pure Lambert here; glossy surfaces use the `phong` or `microfacet` types.
Bsdf make_bsdf(const Material& material, const Hit& hit);

}  // namespace rt
