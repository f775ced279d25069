// Stage 4: every sample warp draws from exactly the density its pdf claims (chi-square), and every
// pdf integrates to 1 over its domain.
#include "04-radiometry/ggx.h"
#include "04-radiometry/warp.h"
#include "support/chi_square.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::subject;

using testing::chi_square_test;
using testing::integrate_2d;
using testing::sphere_chi_square;
using testing::SphereGrid;
using testing::kHalfPi;

constexpr int kSamples = 1000000;

TEST(WarpChiSquare, UniformHemisphere) {
  const SphereGrid grid{10, 40, 0.0, kHalfPi};
  const auto r = sphere_chi_square(grid, kSamples, 1, [](Rng& rng) { return std::optional(sample_uniform_hemisphere(rng.uniform2())); },
                                   [](Vec3 w) { return uniform_hemisphere_pdf(w); });
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(WarpChiSquare, CosineHemisphere) {
  const SphereGrid grid{10, 40, 0.0, kHalfPi};
  const auto r = sphere_chi_square(grid, kSamples, 2, [](Rng& rng) { return std::optional(sample_cosine_hemisphere(rng.uniform2())); },
                                   [](Vec3 w) { return cosine_hemisphere_pdf(w); });
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(WarpChiSquare, UniformSphere) {
  const SphereGrid grid{20, 40, 0.0, testing::kPiD};
  const auto r = sphere_chi_square(grid, kSamples, 3, [](Rng& rng) { return std::optional(sample_uniform_sphere(rng.uniform2())); },
                                   [](Vec3) { return uniform_sphere_pdf(); });
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(WarpChiSquare, UniformCone) {
  for (const float theta_max : {0.05f, 0.6f, 2.5f}) {
    const float cos_max = std::cos(theta_max);
    const SphereGrid grid{10, 40, 0.0, theta_max};
    const auto r = sphere_chi_square(
        grid, kSamples, 4, [&](Rng& rng) { return std::optional(sample_uniform_cone(rng.uniform2(), cos_max)); },
        [&](Vec3 w) { return w.z >= cos_max ? uniform_cone_pdf(cos_max) : 0.0f; });
    EXPECT_TRUE(r.passed) << "theta_max " << theta_max << ": " << r.message;
  }
}

TEST(WarpChiSquare, GgxNormals) {
  for (const float alpha : {0.1f, 0.4f, 1.0f}) {
    const SphereGrid grid{20, 20, 0.0, kHalfPi};
    const auto r = sphere_chi_square(
        grid, kSamples, 5, [&](Rng& rng) { return std::optional(GgxDistribution{alpha}.sample_normal(rng.uniform2())); },
        [&](Vec3 m) { return GgxDistribution{alpha}.normal_pdf(m); });
    EXPECT_TRUE(r.passed) << "alpha " << alpha << ": " << r.message;
  }
}

TEST(WarpChiSquare, GgxVisibleNormals) {
  for (const float alpha : {0.15f, 0.5f, 1.0f})
    for (const float theta_o : {0.0f, 0.8f, 1.45f}) {
      const Vec3 wo(std::sin(theta_o), 0.0f, std::cos(theta_o));
      const SphereGrid grid{20, 40, 0.0, kHalfPi};
      const auto r = sphere_chi_square(
          grid, kSamples, 6, [&](Rng& rng) { return std::optional(GgxDistribution{alpha}.sample_visible_normal(wo, rng.uniform2())); },
          [&](Vec3 m) { return GgxDistribution{alpha}.visible_normal_pdf(wo, m); });
      EXPECT_TRUE(r.passed) << "alpha " << alpha << ", theta_o " << theta_o << ": " << r.message;
    }
}

TEST(WarpChiSquare, UniformTriangle) {
  // Bins on the square of (b1, b2); the triangle b1 + b2 <= 1 covers the bins below the diagonal
  // whole, halves the diagonal ones exactly, and misses the rest. Density 2 (1 / area).
  constexpr int kGrid = 30;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
  const std::vector<Vec3> samples = subject([] {
    std::vector<Vec3> drawn(kSamples);
    Rng rng(8, 0, 0);
    for (Vec3& b : drawn) b = sample_uniform_triangle(rng.uniform2());
    return drawn;
  });
  for (const Vec3 b : samples) {
    ASSERT_NEAR(b.x + b.y + b.z, 1.0f, 1e-6f);
    ASSERT_GE(b.x, 0.0f);
    const int i = std::min(kGrid - 1, int(b.y * kGrid)), j = std::min(kGrid - 1, int(b.z * kGrid));
    observed[size_t(i * kGrid + j)] += 1.0;
  }
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const double covered = i + j + 2 <= kGrid ? 1.0 : (i + j + 1 == kGrid ? 0.5 : 0.0);
      expected[size_t(i * kGrid + j)] = kSamples * 2.0 * covered / (kGrid * kGrid);
    }
  const auto r = chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed) << r.message;
}

// The test has teeth: samples from one warp tested against a slightly different pdf fail.
TEST(DistributionTest, RejectsAWrongPdf) {
  const SphereGrid grid{10, 40, 0.0, kHalfPi};
  auto cosine = [](Rng& rng) { return std::optional(sample_cosine_hemisphere(rng.uniform2())); };
  // Uniform instead of cosine-weighted: grossly wrong.
  EXPECT_FALSE(sphere_chi_square(grid, kSamples, 9, cosine, [](Vec3 w) { return uniform_hemisphere_pdf(w); }).passed);
  // cos^1.05 instead of cos, renormalized: a 5% change in the exponent.
  EXPECT_FALSE(sphere_chi_square(grid, kSamples, 9, cosine, [](Vec3 w) {
                 return w.z > 0.0f ? std::pow(w.z, 1.05f) * 2.05f / (2.0f * kPi) : 0.0f;
               }).passed);
  // GGX visible normals scored against the plain D(m) cos(theta_m) distribution.
  const Vec3 wo = glm::normalize(Vec3(0.7f, 0.0f, 0.7f));
  EXPECT_FALSE(sphere_chi_square(
                   SphereGrid{20, 40, 0.0, kHalfPi}, kSamples, 9,
                   [&](Rng& rng) { return std::optional(GgxDistribution{0.5f}.sample_visible_normal(wo, rng.uniform2())); },
                   [](Vec3 m) { return GgxDistribution{0.5f}.normal_pdf(m); })
                   .passed);
}

// Each pdf integrates to 1 over its domain (Simpson over theta and phi, dw = sin(theta) dtheta dphi).
double integrate_over_sphere(const std::function<double(Vec3)>& pdf, double theta_max = testing::kPiD, int n = 400) {
  return integrate_2d([&](double t, double p) { return pdf(testing::direction_from_angles(t, p)) * std::sin(t); },
                      0.0, theta_max, 0.0, 2.0 * testing::kPiD, n);
}

TEST(WarpPdf, IntegratesToOne) {
  EXPECT_NEAR(subject([&] { return integrate_over_sphere([](Vec3 w) { return uniform_hemisphere_pdf(w); }, kHalfPi); }), 1.0, 1e-5);
  EXPECT_NEAR(subject([&] { return integrate_over_sphere([](Vec3 w) { return cosine_hemisphere_pdf(w); }, kHalfPi); }), 1.0, 1e-5);
  EXPECT_NEAR(subject([&] { return integrate_over_sphere([](Vec3) { return uniform_sphere_pdf(); }); }), 1.0, 1e-5);
  const float cos_max = std::cos(0.6f);
  EXPECT_NEAR(subject([&] { return integrate_over_sphere([&](Vec3) { return uniform_cone_pdf(cos_max); }, 0.6); }), 1.0, 1e-5);
  for (const float alpha : {0.05f, 0.3f, 1.0f}) {
    EXPECT_NEAR(subject([&] { return integrate_over_sphere([&](Vec3 m) { return GgxDistribution{alpha}.normal_pdf(m); }, kHalfPi, 2000); }), 1.0, 1e-3)
        << alpha;
    const Vec3 wo = glm::normalize(Vec3(0.5f, 0.2f, 0.6f));
    EXPECT_NEAR(subject([&] { return integrate_over_sphere([&](Vec3 m) { return GgxDistribution{alpha}.visible_normal_pdf(wo, m); }, kHalfPi, 2000); }),
                1.0, 1e-3)
        << alpha;
  }
  EXPECT_NEAR(subject([&] { return integrate_2d([](double x, double y) { return uniform_disk_pdf(Vec2(float(x), float(y))); }, -1, 1, -1, 1, 2000); }),
              1.0, 1e-2);
}

TEST(WarpEdges, ExtremeNumbersStayOnTheDomain) {
  // The corners of [0, 1)^2, including the largest float below 1.
  const float one_minus = 1.0f - 0x1p-24f;
  for (const float a : {0.0f, 0.5f, one_minus})
    for (const float b : {0.0f, 0.5f, one_minus}) {
      const Vec2 u(a, b);
      const auto [directions, d, t] = subject([&] {
        return std::tuple(std::vector<Vec3>{sample_uniform_hemisphere(u), sample_cosine_hemisphere(u), sample_uniform_sphere(u),
                                            sample_uniform_cone(u, 0.3f), GgxDistribution{0.2f}.sample_normal(u),
                                            GgxDistribution{0.2f}.sample_visible_normal(glm::normalize(Vec3(1, 0, 1e-4f)), u)},
                          sample_uniform_disk(u), sample_uniform_triangle(u));
      });
      for (const Vec3 w : directions) {
        EXPECT_TRUE(is_finite(w)) << a << " " << b;
        EXPECT_NEAR(glm::length(w), 1.0f, 1e-5f) << a << " " << b;
      }
      EXPECT_LE(glm::length(d), 1.0f + 1e-6f);
      EXPECT_GE(std::min({t.x, t.y, t.z}), 0.0f);
    }
}

// Every warp has its inverse: sample then invert gives back u, over a grid of the square that
// avoids only its edges (where the azimuth wraps or the disk's centre is one point for many u).
TEST(WarpInverses, InvertingASampleGivesBackItsNumbers) {
  int checked = 0;
  for (int i = 1; i < 40; ++i)
    for (int j = 1; j < 40; ++j) {
      const Vec2 u(float(i) / 40.0f, float(j) / 40.0f);
      auto expect_back = [&](Vec2 back, const char* warp) {
        EXPECT_NEAR(back.x, u.x, 2e-5f) << warp << " at " << u.x << ", " << u.y;
        EXPECT_NEAR(back.y, u.y, 2e-5f) << warp << " at " << u.x << ", " << u.y;
        ++checked;
      };
      const auto [hemisphere, sphere, cosine, cone, triangle] = subject([&] {
        return std::tuple(sample_uniform_hemisphere(u), sample_uniform_sphere(u), sample_cosine_hemisphere(u),
                          sample_uniform_cone(u, 0.6f), sample_uniform_triangle(u));
      });
      expect_back(invert_uniform_hemisphere(hemisphere), "uniform hemisphere");
      expect_back(invert_uniform_sphere(sphere), "uniform sphere");
      expect_back(invert_cosine_hemisphere(cosine), "cosine hemisphere");
      expect_back(invert_uniform_cone(cone, 0.6f), "cone");
      expect_back(invert_uniform_triangle(triangle), "triangle");
    }
  EXPECT_EQ(checked, 5 * 39 * 39);
}

}  // namespace
}  // namespace rt
