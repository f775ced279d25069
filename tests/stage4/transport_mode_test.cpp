// Radiance and importance through one scattering event (stage 4's TransportMode): the BSDF models'
// part, glass's (eta_t / eta_i)^2, and the shading frame's part, the shading normal's correction.
// The light-traced image that depends on both is tests/stage6/caustic_test.cpp's. Glass refracts
// through stage 2's tasks and Phong is a task, so what they give comes through subject().
#include "04-radiometry/shading_point.h"

#include "stage4/records.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <tuple>
#include <vector>

namespace rt {
namespace {

using testing::subject;

Vec3 unit(float x, float y, float z) { return glm::normalize(Vec3(x, y, z)); }

TEST(TransportMode, GlassRefractsRadianceSqueezedAndImportanceAsFlux) {
  for (const DielectricBsdf glass : {DielectricBsdf{1.0f, 1.5f}, DielectricBsdf{1.5f, 1.0f}}) {
    const Vec3 wo = unit(0.3f, 0.0f, 1.0f);  // inside the critical angle from either side
    const float squeeze = (glass.eta_outside / glass.eta_inside) * (glass.eta_outside / glass.eta_inside);
    for (const float u_lobe : {0.0f, 0.999f}) {
      const auto radiance = subject([&] { return glass.sample(wo, Vec2(0.5f), u_lobe, TransportMode::radiance); });
      const auto importance = subject([&] { return glass.sample(wo, Vec2(0.5f), u_lobe, TransportMode::importance); });
      ASSERT_TRUE(radiance && importance);
      EXPECT_EQ(radiance->wi, importance->wi) << "the mode changes no direction";
      EXPECT_EQ(radiance->pdf, importance->pdf) << "nor a lobe's probability";
      const bool refracted = radiance->wi.z < 0.0f;
      EXPECT_EQ(refracted, u_lobe > 0.5f);
      // Reflection weighs 1 for both; refraction (eta_o / eta_i)^2 for radiance, 1 for importance,
      // so that a light path's flux is conserved: F + (1 - F) = 1.
      EXPECT_FLOAT_EQ(radiance->weight.x, refracted ? squeeze : 1.0f) << glass.eta_outside;
      EXPECT_EQ(importance->weight, Color(1.0f)) << glass.eta_outside;
    }
    // The Bsdf's sample() carries radiance unless told otherwise, as stages 4 and 5 use it.
    const auto [by_default, radiance, importance] = subject([&] {
      return std::tuple(Bsdf(glass).sample(wo, Vec2(0.5f), 0.999f),
                        glass.sample(wo, Vec2(0.5f), 0.999f, TransportMode::radiance),
                        Bsdf(glass).sample(wo, Vec2(0.5f), 0.999f, TransportMode::importance));
    });
    ASSERT_TRUE(by_default && radiance && importance);
    EXPECT_EQ(by_default->weight, radiance->weight);
    EXPECT_EQ(importance->weight, Color(1.0f));
  }
  // Beyond the critical angle, inside the glass: total internal reflection, weight 1 for both.
  const DielectricBsdf inside{1.5f, 1.0f};
  for (const TransportMode mode : {TransportMode::radiance, TransportMode::importance}) {
    const auto s = subject([&] { return inside.sample(unit(2.0f, 0.0f, 1.0f), Vec2(0.5f), 0.999f, mode); });
    ASSERT_TRUE(s);
    EXPECT_GT(s->wi.z, 0.0f);
    EXPECT_EQ(s->weight, Color(1.0f));
  }
}

// A point whose shading normal leans from its geometric one (+z), as on a smooth-shaded mesh.
ShadingPoint leaning(const Bsdf& bsdf, Vec3 shading_normal, Vec3 towards_viewer) {
  Hit hit;
  hit.normal = Vec3(0.0f, 0.0f, 1.0f);
  hit.shading_normal = shading_normal;
  const Frame frame = Frame::from_normal(shading_normal);
  return ShadingPoint{hit, bsdf, frame, frame.to_local(towards_viewer)};
}

// One sample of a shading point in both modes: the radiance sample, the importance sample, the
// BSDF's own sample, and f_eff(wi, wo) = f_s(wi, wo) |wo.ns| / |wo.ng| for the importance sample's
// wi (world directions).
using BothModes = std::tuple<std::optional<BsdfSample>, std::optional<BsdfSample>, std::optional<BsdfSample>, Color>;

BothModes both_modes(const ShadingPoint& at, Vec3 wo_world, Vec2 u, float u_lobe) {
  const auto radiance = at.sample(u, u_lobe);
  const auto importance = at.sample(u, u_lobe, TransportMode::importance);
  Color reverse(0.0f);
  if (importance) {
    const Vec3 wi_world = at.frame.to_world(importance->wi);
    reverse = at.bsdf.eval(at.frame.to_local(wi_world), at.frame.to_local(wo_world)) *
              std::abs(glm::dot(wo_world, at.hit.shading_normal)) / std::abs(glm::dot(wo_world, at.hit.normal));
  }
  return {radiance, importance, at.bsdf.sample(at.wo, u, u_lobe), reverse};
}

// The adjoint of the scattering that a path tracer weighs with the shading cosine,
// f_eff(wo, wi) = f_s(wo, wi) |wi.ns| / |wi.ng| (Veach's thesis, section 5.3), is
// f*(wo, wi) = f_eff(wi, wo): an importance sample's weight times its pdf over |wi.ng| must give it.
TEST(TransportMode, ShadingNormalsTurnTheCosinesRoundForImportance) {
  const Vec3 ns = unit(0.5f, 0.2f, 1.0f), ng(0.0f, 0.0f, 1.0f);
  const Bsdf phong(PhongBrdf{Color(0.3f), Color(0.5f), 12.0f});
  for (const Vec3 wo_world : {unit(1.0f, 0.0f, 1.0f), unit(-0.4f, 0.7f, 1.0f), unit(0.1f, -0.2f, 1.0f)}) {
    const ShadingPoint at = leaning(phong, ns, wo_world);
    const std::vector<BothModes> samples = subject([&] {
      std::vector<BothModes> out;
      for (int i = 0; i < 16; ++i)
        out.push_back(both_modes(at, wo_world, Vec2((float(i % 4) + 0.5f) / 4.0f, (float(i / 4) + 0.5f) / 4.0f),
                                 float(i) / 16.0f));
      return out;
    });
    int checked = 0;
    for (size_t i = 0; i < samples.size(); ++i) {
      const auto& [radiance, importance, own, reverse] = samples[i];
      ASSERT_EQ(radiance.has_value(), importance.has_value());
      if (!radiance) continue;
      ASSERT_TRUE(own);
      EXPECT_EQ(radiance->wi, importance->wi);
      EXPECT_EQ(radiance->weight, own->weight) << "radiance: the BSDF's own weight";
      const Vec3 wi_world = at.frame.to_world(importance->wi);
      if (std::abs(glm::dot(wi_world, ng)) < 0.05f) continue;  // grazing the geometry: the factor is ill-conditioned
      const Color adjoint = importance->weight * importance->pdf / std::abs(glm::dot(wi_world, ng));
      EXPECT_NEAR(adjoint.x, reverse.x, 1e-4f * reverse.x) << "sample " << i;
      EXPECT_GT(reverse.x, 0.0f) << "sample " << i;
      // ... which is not the radiance weight's f_eff(wo, wi): the correction is not 1 here.
      EXPECT_GT(std::abs(radiance->weight.x - importance->weight.x), 1e-3f * radiance->weight.x) << "sample " << i;
      ++checked;
    }
    EXPECT_GE(checked, 8);
  }
  // Where the two normals agree the modes weigh alike, and glass's refraction, corrected the same
  // way, stays unsqueezed.
  const ShadingPoint flat = leaning(phong, ng, unit(1.0f, 0.0f, 1.0f));
  const auto [flat_radiance, flat_importance] = subject([&] {
    return std::pair(flat.sample(Vec2(0.3f), 0.7f), flat.sample(Vec2(0.3f), 0.7f, TransportMode::importance));
  });
  ASSERT_TRUE(flat_radiance && flat_importance);
  EXPECT_EQ(flat_radiance->weight, flat_importance->weight);
  const Vec3 wo_world = unit(0.2f, 0.0f, 1.0f);
  const ShadingPoint glass = leaning(Bsdf(DielectricBsdf{1.0f, 1.5f}), ns, wo_world);
  const auto refracted = subject([&] { return glass.sample(Vec2(0.5f), 0.999f, TransportMode::importance); });
  ASSERT_TRUE(refracted && refracted->wi.z < 0.0f);
  const Vec3 wi_world = glass.frame.to_world(refracted->wi);
  EXPECT_NEAR(refracted->weight.x,
              std::abs(glm::dot(wo_world, ns)) * std::abs(glm::dot(wi_world, ng)) /
                  (std::abs(glm::dot(wo_world, ng)) * std::abs(glm::dot(wi_world, ns))),
              1e-5f);
}

}  // namespace
}  // namespace rt
