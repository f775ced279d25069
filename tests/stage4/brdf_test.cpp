// Stage 4: every BRDF keeps the contract of 04-radiometry/brdf.h: its sampler draws from its pdf
// (chi-square), the pdf integrates to what the sampler delivers, it is reciprocal, and it never
// reflects more than it receives.
#include "02-whitted/optics.h"
#include "04-radiometry/bsdf.h"
#include "04-radiometry/warp.h"
#include "support/chi_square.h"
#include "stage4/records.h"
#include "support/sample_mean.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <limits>

namespace rt {
namespace {

using testing::integrate_2d;
using testing::sphere_chi_square;
using testing::SphereGrid;
using testing::kHalfPi;

Vec3 direction(float theta, float phi = 0.0f) {
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// The glossy models over the parameters the tests sweep: roughness from sharp to very rough.
std::vector<std::pair<std::string, Bsdf>> glossy_models() {
  std::vector<std::pair<std::string, Bsdf>> models;
  models.emplace_back("lambert", Bsdf(LambertBrdf{Color(0.6f, 0.5f, 0.4f)}));
  for (const float n : {1.0f, 20.0f, 200.0f}) {
    models.emplace_back("phong specular-only n=" + std::to_string(n), Bsdf(PhongBrdf{Color(0.0f), Color(0.9f), n}));
    models.emplace_back("phong mixed n=" + std::to_string(n), Bsdf(PhongBrdf{Color(0.3f), Color(0.6f), n}));
  }
  for (const float alpha : {0.05f, 0.2f, 0.6f, 1.0f})
    models.emplace_back("ggx alpha=" + std::to_string(alpha), Bsdf(MicrofacetBrdf{Color(1.0f, 0.8f, 0.5f), GgxDistribution{alpha}}));
  return models;
}

TEST(BrdfChiSquare, SamplersDrawFromTheirPdf) {
  int tested = 0;
  for (const auto& [name, brdf] : glossy_models()) {
    // Very sharp lobes concentrate in a bin or two, where the test says little; their other
    // properties are tested below.
    if (name.find("alpha=0.05") != std::string::npos || name.find("n=200") != std::string::npos) continue;
    for (const float theta_o : {0.3f, 1.2f}) {
      const Vec3 wo = direction(theta_o, 0.4f);
      const SphereGrid grid{20, 40, 0.0, kHalfPi};
      const auto r = sphere_chi_square(
          grid, 1000000, 11,
          [&](Rng& rng) -> std::optional<Vec3> {
            const Vec2 u = rng.uniform2();
            const auto s = RT_GRADED(brdf.sample)(wo, u, rng.uniform());
            if (!s) return std::nullopt;
            return s->wi;
          },
          [&](Vec3 wi) { return RT_GRADED(brdf.pdf)(wo, wi); });
      EXPECT_TRUE(r.passed) << name << ", theta_o " << theta_o << ": " << r.message;
      ++tested;
    }
  }
  EXPECT_EQ(tested, 16);
}

TEST(BrdfChiSquare, RejectsAWrongGgxJacobian) {
  // The density of the reflected direction without the Jacobian 1 / (4 |wo . m|) of the reflection.
  const MicrofacetBrdf brdf{Color(1.0f), GgxDistribution{0.4f}};
  const Vec3 wo = direction(0.9f);
  const auto r = sphere_chi_square(
      SphereGrid{20, 40, 0.0, kHalfPi}, 1000000, 12,
      [&](Rng& rng) -> std::optional<Vec3> {
        const Vec2 u = rng.uniform2();
        const auto s = RT_GRADED(brdf.sample)(wo, u, 0.0f);
        return s ? std::optional(s->wi) : std::nullopt;
      },
      [&](Vec3 wi) {
        if (wi.z <= 0.0f) return 0.0f;
        const Vec3 h = glm::normalize(wi + wo);
        return GgxDistribution{0.4f}.visible_normal_pdf(wo, h);
      });
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(BrdfPdf, SampleAndPdfAgree) {
  for (const auto& [name, brdf] : glossy_models()) {
    Rng rng(13, 0, 0);
    for (int k = 0; k < 2000; ++k) {
      const Vec3 wo = sample_uniform_hemisphere(rng.uniform2());
      const Vec2 u = rng.uniform2();
      const auto s = RT_GRADED(brdf.sample)(wo, u, rng.uniform());
      if (!s) continue;
      ASSERT_FALSE(s->delta);
      ASSERT_GT(s->wi.z, 0.0f) << name;
      EXPECT_NEAR(s->pdf, RT_GRADED(brdf.pdf)(wo, s->wi), 1e-3f * s->pdf) << name;
      const Color expected = RT_GRADED(brdf.eval)(wo, s->wi) * s->wi.z / s->pdf;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(s->weight[c], expected[c], 1e-4f * (1.0f + expected[c])) << name;
    }
  }
}

TEST(BrdfPdf, IntegratesToWhatTheSamplerDelivers) {
  // Over the sphere, pdf integrates to 1 minus the fraction of samples wasted below the surface.
  for (const auto& [name, brdf] : glossy_models()) {
    if (name.find("alpha=0.05") != std::string::npos || name.find("n=200") != std::string::npos) continue;
    const Vec3 wo = direction(1.0f, 0.3f);
    const double integral = RT_GRADED(integrate_2d)(
        [&](double t, double p) { return RT_GRADED(brdf.pdf)(wo, testing::direction_from_angles(t, p)) * std::sin(t); },
        0.0, kHalfPi, 0.0, 2.0 * testing::kPiD, 600);
    constexpr int kN = 400000;
    int delivered = 0;
    Rng rng(14, 0, 0);
    for (int k = 0; k < kN; ++k) {
      const Vec2 u = rng.uniform2();
      delivered += RT_GRADED(brdf.sample)(wo, u, rng.uniform()) ? 1 : 0;
    }
    const double fraction = double(delivered) / kN;
    const double sigma = std::sqrt(fraction * (1.0 - fraction) / kN);
    EXPECT_NEAR(integral, fraction, 4.0 * sigma + 2e-3) << name;
    EXPECT_LE(integral, 1.0 + 1e-3) << name;
  }
}

TEST(BrdfProperties, Reciprocity) {
  for (const auto& [name, brdf] : glossy_models()) {
    Rng rng(15, 0, 0);
    for (int k = 0; k < 5000; ++k) {
      const Vec3 a = sample_uniform_hemisphere(rng.uniform2()), b = sample_uniform_hemisphere(rng.uniform2());
      const Color fab = RT_GRADED(brdf.eval)(b, a), fba = RT_GRADED(brdf.eval)(a, b);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(fab[c], fba[c], 1e-5f * (1.0f + fab[c])) << name;
    }
  }
}

using testing::Estimate;

// Directional albedo rho(wo) = integral f_r cos(theta_i) dwi, estimated with the model's own
// sampler (mean of the weights) and its standard error.
Estimate directional_albedo(const Bsdf& brdf, Vec3 wo, int channel, int samples, std::uint64_t seed) {
  Rng rng(seed, 0, 0);
  testing::SampleMean m;
  for (int k = 0; k < samples; ++k) {
    const Vec2 u = rng.uniform2();
    const auto s = RT_GRADED(brdf.sample)(wo, u, rng.uniform());
    m.add(s ? double(s->weight[channel]) : 0.0);
  }
  return m.estimate();
}

TEST(BrdfProperties, NoModelReflectsMoreThanItReceives) {
  // White versions (reflectance 1) are the hardest case.
  std::vector<std::pair<std::string, Bsdf>> white;
  for (const float n : {0.0f, 1.0f, 10.0f, 100.0f, 1000.0f})
    white.emplace_back("phong n=" + std::to_string(n), Bsdf(PhongBrdf{Color(0.0f), Color(1.0f), n}));
  white.emplace_back("phong half and half", Bsdf(PhongBrdf{Color(0.5f), Color(0.5f), 30.0f}));
  for (const float alpha : {0.01f, 0.1f, 0.3f, 0.6f, 1.0f})
    white.emplace_back("ggx alpha=" + std::to_string(alpha), Bsdf(MicrofacetBrdf{Color(1.0f), GgxDistribution{alpha}}));
  for (const auto& [name, brdf] : white)
    for (const float theta_o : {0.0f, 0.4f, 0.8f, 1.2f, 1.5f}) {
      const Estimate a = RT_GRADED(directional_albedo)(brdf, direction(theta_o), 0, 100000, 16);
      EXPECT_LE(a.mean, 1.0 + 3.0 * a.standard_error + 1e-5) << name << ", theta_o " << theta_o;
    }
}

TEST(BrdfProperties, NormalizationsAreExact) {
  // The normalized Phong lobe's albedo is exactly rho_s at normal incidence ((n + 2) / (2 pi)).
  for (const float n : {1.0f, 10.0f, 100.0f}) {
    const Estimate a =
        RT_GRADED(directional_albedo)(Bsdf(PhongBrdf{Color(0.0f), Color(1.0f), n}), Vec3(0, 0, 1), 0, 200000, 17);
    EXPECT_NEAR(a.mean, 1.0, 4.0 * a.standard_error + 1e-4) << n;
  }
  // A smooth GGX mirror with F0 = 1 reflects nearly everything at normal incidence, and loses
  // energy (single scattering) as it gets rough.
  const Estimate smooth = RT_GRADED(directional_albedo)(Bsdf(MicrofacetBrdf{Color(1.0f), GgxDistribution{0.01f}}),
                                                        Vec3(0, 0, 1), 0, 100000, 18);
  EXPECT_GT(smooth.mean, 0.995);
  const Estimate rough = RT_GRADED(directional_albedo)(Bsdf(MicrofacetBrdf{Color(1.0f), GgxDistribution{1.0f}}),
                                                       direction(1.2f), 0, 100000, 18);
  EXPECT_LT(rough.mean, 0.9);
}

TEST(BrdfProperties, GgxAlbedoMatchesQuadrature) {
  // The single-scattering albedo of white GGX (F = 1, height-correlated Smith G2), by importance
  // sampling and by Simpson quadrature of f_r cos over the hemisphere, which share nothing but
  // eval(). The values are the table in docs/stage4.md; the energy lost at alpha = 1 is what
  // multiple-scattering models (Heitz et al. 2016; Kulla & Conty 2017) put back.
  const struct {
    float alpha, theta_o_degrees;
    double albedo;
  } table[] = {{0.3f, 0.0f, 0.8774}, {0.3f, 60.0f, 0.8217}, {0.5f, 0.0f, 0.6878}, {0.5f, 80.0f, 0.8053},
               {1.0f, 0.0f, 0.3069}, {1.0f, 60.0f, 0.4507}};
  for (const auto& row : table) {
    const Bsdf brdf(MicrofacetBrdf{Color(1.0f), GgxDistribution{row.alpha}});
    const Vec3 wo = direction(radians(row.theta_o_degrees));
    const double quadrature = RT_GRADED(integrate_2d)(
        [&](double t, double p) {
          const Vec3 wi = testing::direction_from_angles(t, p);
          return double(RT_GRADED(brdf.eval)(wo, wi).x) * wi.z * std::sin(t);
        },
        0.0, kHalfPi, 0.0, 2.0 * testing::kPiD, 400);
    const Estimate sampled = RT_GRADED(directional_albedo)(brdf, wo, 0, 200000, 21);
    EXPECT_NEAR(quadrature, row.albedo, 5e-4) << row.alpha << " " << row.theta_o_degrees;
    EXPECT_NEAR(sampled.mean, quadrature, 4.0 * sampled.standard_error + 1e-4) << row.alpha << " " << row.theta_o_degrees;
  }
}

TEST(BrdfProperties, WhiteLambertReflectsExactlyEverything) {
  const Bsdf white(LambertBrdf{Color(1.0f)});
  // Cosine sampling makes every weight exactly 1.
  for (const float theta_o : {0.0f, 0.7f, 1.55f}) {
    const Estimate a = RT_GRADED(directional_albedo)(white, direction(theta_o), 1, 10000, 19);
    EXPECT_NEAR(a.mean, 1.0, 1e-6);
    EXPECT_LT(a.standard_error, 1e-6);
  }
  // And by quadrature: the integral of (1 / pi) cos over the hemisphere.
  const double q = RT_GRADED(integrate_2d)(
      [&](double t, double p) {
        const Vec3 wi = testing::direction_from_angles(t, p);
        return double(RT_GRADED(white.eval)(direction(0.5f), wi).x) * wi.z * std::sin(t);
      },
      0.0, kHalfPi, 0.0, 2.0 * testing::kPiD, 200);
  EXPECT_NEAR(q, 1.0, 1e-6);
}

TEST(BrdfProperties, NothingBelowTheSurface) {
  for (const auto& [name, brdf] : glossy_models()) {
    EXPECT_EQ(RT_GRADED(brdf.eval)(direction(0.3f), direction(2.0f)), Color(0.0f)) << name;
    EXPECT_EQ(RT_GRADED(brdf.eval)(direction(2.0f), direction(0.3f)), Color(0.0f)) << name;
    EXPECT_EQ(RT_GRADED(brdf.pdf)(direction(0.3f), direction(2.0f)), 0.0f) << name;
    EXPECT_FALSE(RT_GRADED(brdf.sample)(direction(2.0f), Vec2(0.3f), 0.5f)) << name;
  }
}

// The exact boundary the contracts name: a direction lying in the tangent plane (z = +0 or -0) is
// not above the surface. There a model returns exactly 0, never the 0/0 of a cosine in a
// denominator (the microfacet model divides by 4 cos_i cos_o): "<=" written as "<" survived every
// test that only looked above or below. Just above it, the smallest positive z, everything is finite.
TEST(BrdfProperties, ExactlyInTheHorizonIsZeroAndJustAboveIsFinite) {
  const float tiny = std::numeric_limits<float>::denorm_min();
  for (const auto& [name, brdf] : glossy_models())
    for (const float z : {0.0f, -0.0f}) {
      const Vec3 horizon(1.0f, 0.0f, z), up = direction(0.4f, 2.0f);
      EXPECT_EQ(RT_GRADED(brdf.eval)(up, horizon), Color(0.0f)) << name << ", wi in the horizon";
      EXPECT_EQ(RT_GRADED(brdf.eval)(horizon, up), Color(0.0f)) << name << ", wo in the horizon";
      EXPECT_EQ(RT_GRADED(brdf.eval)(horizon, horizon), Color(0.0f)) << name << ", both";
      EXPECT_EQ(RT_GRADED(brdf.pdf)(up, horizon), 0.0f) << name;
      EXPECT_EQ(RT_GRADED(brdf.pdf)(horizon, up), 0.0f) << name;
      EXPECT_FALSE(RT_GRADED(brdf.sample)(horizon, Vec2(0.3f, 0.7f), 0.5f)) << name << ": no sample from the horizon";
      const Vec3 grazing(1.0f, 0.0f, tiny);
      const Color f = RT_GRADED(brdf.eval)(up, grazing);
      EXPECT_TRUE(is_finite(f) && min_component(f) >= 0.0f) << name;
      EXPECT_TRUE(std::isfinite(RT_GRADED(brdf.pdf)(up, grazing))) << name;
    }
}

// A delta lobe (mirror, glass) is reached only by sampling it: its eval and pdf are exactly 0 for
// every pair of directions, its own reflection and refraction included. BDPT relies on it: a
// connection to a delta vertex returns before any evaluation, and where it did not (the guard's
// "||" written as "&&"), the value would still be 0 (grading/equivalent-mutants.json).
TEST(DeltaLobes, EvalAndPdfAreZeroForEveryPairOfDirections) {
  const std::pair<const char*, Bsdf> models[] = {{"mirror", Bsdf(MirrorBrdf{Color(0.9f)})},
                                                 {"glass entered", Bsdf(DielectricBsdf{1.0f, 1.5f})},
                                                 {"glass left", Bsdf(DielectricBsdf{1.5f, 1.0f})}};
  for (const auto& [name, bsdf] : models)
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        const Vec3 wo = direction(0.27f * float(i), 0.5f * float(j)), wi = direction(0.27f * float(j), 0.9f * float(i));
        EXPECT_EQ(RT_GRADED(bsdf.eval)(wo, wi), Color(0.0f)) << name;
        EXPECT_EQ(RT_GRADED(bsdf.pdf)(wo, wi), 0.0f) << name;
        if (const auto s = RT_GRADED(bsdf.sample)(wo, Vec2(0.5f), 0.3f)) {
          EXPECT_EQ(RT_GRADED(bsdf.eval)(wo, s->wi), Color(0.0f)) << name << ": its own sample";
          EXPECT_EQ(RT_GRADED(bsdf.pdf)(wo, s->wi), 0.0f) << name;
        }
      }
}

// A caller draws the lobe number only for a model that says it reads it (the path tracer saves a
// number per bounce that way, and passes a constant otherwise): a model whose samples depend on
// u_lobe and does not say so would always take the same lobe there.
TEST(BrdfProperties, ModelsThatReadTheLobeNumberSaySo) {
  std::vector<std::pair<std::string, Bsdf>> models = glossy_models();
  models.emplace_back("mirror", Bsdf(MirrorBrdf{Color(0.9f)}));
  models.emplace_back("glass entered", Bsdf(DielectricBsdf{1.0f, 1.5f}));
  models.emplace_back("glass left", Bsdf(DielectricBsdf{1.5f, 1.0f}));
  for (const auto& [name, bsdf] : models) {
    int differ = 0;
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) {
        const Vec2 u((i + 0.5f) / 16.0f, (j + 0.5f) / 16.0f);
        const Vec3 wo = direction(0.1f + 0.09f * float(i), 0.4f * float(j));
        const auto low = RT_GRADED(bsdf.sample)(wo, u, 0.01f), high = RT_GRADED(bsdf.sample)(wo, u, 0.99f);
        if (low.has_value() != high.has_value() || (low && (low->wi != high->wi || low->weight != high->weight)))
          ++differ;
      }
    if (differ > 0) {
      EXPECT_TRUE(bsdf.has_lobe_choice()) << name << ": " << differ << " of 256 samples depend on u_lobe";
    }
    if (name.starts_with("phong mixed") || name.starts_with("glass")) {
      EXPECT_GT(differ, 0) << name << ": two lobes, so u_lobe must matter somewhere";
    }
  }
}

TEST(DeltaLobes, MirrorReflectsAboutTheNormal) {
  const Bsdf mirror(MirrorBrdf{Color(0.9f, 0.8f, 0.7f)});
  EXPECT_TRUE(mirror.is_delta());
  const Vec3 wo = direction(0.6f, 1.0f);
  const auto s = RT_GRADED(mirror.sample)(wo, Vec2(0.2f), 0.7f);
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->delta);
  EXPECT_NEAR(s->wi.x, -wo.x, 1e-7f);
  EXPECT_NEAR(s->wi.y, -wo.y, 1e-7f);
  EXPECT_NEAR(s->wi.z, wo.z, 1e-7f);
  EXPECT_EQ(s->weight, Color(0.9f, 0.8f, 0.7f));
  EXPECT_EQ(RT_GRADED(mirror.eval)(wo, s->wi), Color(0.0f));
  EXPECT_EQ(RT_GRADED(mirror.pdf)(wo, s->wi), 0.0f);
}

TEST(DeltaLobes, GlassReflectsWithTheFresnelProbability) {
  const Bsdf glass(DielectricBsdf{1.0f, 1.5f});
  const Vec3 wo = direction(1.0f);
  const float f = RT_GRADED(fresnel_dielectric)(wo.z, 1.0f, 1.5f);
  constexpr int kN = 200000;
  int reflected = 0;
  Rng rng(20, 0, 0);
  for (int k = 0; k < kN; ++k) {
    const auto s = RT_GRADED(glass.sample)(wo, Vec2(0.5f), rng.uniform());
    ASSERT_TRUE(s);
    if (s->wi.z > 0.0f) {
      ++reflected;
      EXPECT_EQ(s->weight, Color(1.0f));
      EXPECT_FLOAT_EQ(s->pdf, f);
    } else {
      // Entering the denser side: radiance seen from outside is (1 / 1.5)^2 of the inside's.
      EXPECT_NEAR(s->weight.x, 1.0f / 2.25f, 1e-6f);
      EXPECT_FLOAT_EQ(s->pdf, 1.0f - f);
      // Snell: sin(theta_t) = sin(theta_i) / 1.5.
      EXPECT_NEAR(std::sqrt(s->wi.x * s->wi.x + s->wi.y * s->wi.y), std::sin(1.0f) / 1.5f, 1e-5f);
    }
  }
  const double sigma = std::sqrt(f * (1.0 - f) / kN);
  EXPECT_NEAR(double(reflected) / kN, f, 4.0 * sigma);
  // From inside beyond the critical angle (asin(1 / 1.5) = 41.8 degrees): always reflected.
  const auto tir = testing::subject([] {
    return Bsdf(DielectricBsdf{1.5f, 1.0f}).sample(direction(0.8f), Vec2(0.5f), 0.999f);
  });
  ASSERT_TRUE(tir);
  EXPECT_GT(tir->wi.z, 0.0f);
}

// A checker alternates the diffuse albedo for phong as for diffuse: phong once read `albedo` alone.
TEST(MakeBsdf, PhongReadsTheCheckerAlbedoAtTheHit) {
  Material phong;
  phong.type = MaterialType::phong;
  phong.albedo = Color(0.1f);
  phong.specular = Color(0.2f);
  phong.checker = Checker{Color(0.7f), 1.0f};
  Hit a, b;
  a.point = Vec3(0.2f, 0.2f, 0.2f);  // the centred cell: the material's albedo
  b.point = Vec3(1.2f, 0.2f, 0.2f);  // the next one along x: the checker's
  // Each model's (diffuse, specular), or nothing where make_bsdf made no phong.
  const auto phong_at = [&](const Hit& hit) {
    return testing::subject([&]() -> std::optional<std::pair<Color, Color>> {
      const Bsdf bsdf = make_bsdf(phong, hit);
      const auto* model = std::get_if<PhongBrdf>(&bsdf.model());
      if (!model) return std::nullopt;
      return std::pair(model->diffuse, model->specular);
    });
  };
  const auto at_a = phong_at(a), at_b = phong_at(b);
  ASSERT_TRUE(at_a && at_b);
  EXPECT_EQ(at_a->first, Color(0.1f));
  EXPECT_EQ(at_b->first, Color(0.7f));
  EXPECT_EQ(at_b->second, Color(0.2f));
}

TEST(MakeBsdf, GlassKnowsWhichSideItIsEnteredFrom) {
  Material glass;
  glass.type = MaterialType::dielectric;
  glass.ior = 1.5f;
  Hit front, back;
  front.front_face = true;
  back.front_face = false;
  // The model's (eta outside, eta inside), or nothing where make_bsdf made no glass.
  const auto glass_at = [&](const Hit& hit) {
    return testing::subject([&]() -> std::optional<std::pair<float, float>> {
      const Bsdf bsdf = make_bsdf(glass, hit);
      const auto* model = std::get_if<DielectricBsdf>(&bsdf.model());
      if (!model) return std::nullopt;
      return std::pair(model->eta_outside, model->eta_inside);
    });
  };
  const auto from_outside = glass_at(front), from_inside = glass_at(back);
  ASSERT_TRUE(from_outside && from_inside);
  EXPECT_EQ(from_outside->first, 1.0f);
  EXPECT_EQ(from_outside->second, 1.5f);
  EXPECT_EQ(from_inside->first, 1.5f);
  EXPECT_EQ(from_inside->second, 1.0f);
}

}  // namespace
}  // namespace rt
