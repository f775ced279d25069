// Hidden tests of stage 4: moments of the warps that no visible test checks, Lambert at random
// albedos, the area-to-solid-angle conversion at random values, and a triangle light's irradiance
// against a numerical integral over the triangle.
#include "04-radiometry/emitters.h"
#include "04-radiometry/lambert.h"
#include "04-radiometry/radiometry.h"
#include "04-radiometry/warp.h"
#include "common/random.h"
#include "stage4/records.h"
#include "support/sample_mean.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using Mean = testing::SampleMean;

TEST(HiddenWarp, CosineHemisphereHasMeanCosineTwoThirds) {
  // E[cos] under p = cos / pi is (1/pi) * integral of cos^2 = 2/3; E[cos^2] = 1/2.
  Rng rng(2718, 0, 0);
  Mean cos1, cos2;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 w = RT_GRADED(sample_cosine_hemisphere)(rng.uniform2());
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-4f);
    cos1.add(w.z);
    cos2.add(double(w.z) * w.z);
  }
  EXPECT_NEAR(cos1.mean(), 2.0 / 3.0, 4 * cos1.standard_error());
  EXPECT_NEAR(cos2.mean(), 0.5, 4 * cos2.standard_error());
}

TEST(HiddenWarp, TriangleBarycentricsHaveTheRightMoments) {
  // Uniform on the triangle: each barycentric has mean 1/3 and E[b^2] = 1/6.
  Rng rng(1618, 0, 0);
  Mean b1, b1_squared;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 b = RT_GRADED(sample_uniform_triangle)(rng.uniform2());
    ASSERT_NEAR(b.x + b.y + b.z, 1.0f, 1e-5f);
    b1.add(b.y);
    b1_squared.add(double(b.y) * b.y);
  }
  EXPECT_NEAR(b1.mean(), 1.0 / 3.0, 4 * b1.standard_error());
  EXPECT_NEAR(b1_squared.mean(), 1.0 / 6.0, 4 * b1_squared.standard_error());
}

TEST(HiddenLambert, RandomAlbedosGiveRhoOverPiAndWeightRho) {
  Rng rng(99991, 0, 0);
  for (int i = 0; i < 200; ++i) {
    const Color rho(rng.uniform(), rng.uniform(), rng.uniform());
    const LambertBrdf brdf{rho};
    const Vec3 wo = RT_GRADED(sample_cosine_hemisphere)(rng.uniform2()),
               wi = RT_GRADED(sample_cosine_hemisphere)(rng.uniform2());
    const Color f = RT_GRADED(brdf.eval)(wo, wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], rho[c] / kPi, 1e-6f);
    const std::optional<BsdfSample> s = RT_GRADED(brdf.sample)(wo, rng.uniform2(), rng.uniform());
    ASSERT_TRUE(s);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s->weight[c], rho[c], 1e-5f);
    EXPECT_NEAR(s->pdf, s->wi.z / kPi, 1e-5f);
  }
}

TEST(HiddenRadiometry, AreaToSolidAngleAtRandomValues) {
  Rng rng(4040, 0, 0);
  for (int i = 0; i < 200; ++i) {
    const float p = 0.1f + rng.uniform(), r = 0.5f + 5.0f * rng.uniform(), c = 0.05f + 0.95f * rng.uniform();
    EXPECT_NEAR(RT_GRADED(area_to_solid_angle_pdf)(p, r, c), p * r * r / c, 1e-4f * p * r * r / c);
  }
}

TEST(HiddenEmitter, TriangleLightMatchesAMidpointQuadrature) {
  // E at a floor point under a tilted triangle of radiance 1, by light sampling, against the
  // integral of cos cos' / r^2 over the triangle by a fine midpoint rule in double.
  const TriangleEmitter light{Vec3(-0.7, 1.3, 0.2), Vec3(0.9, 1.1, -0.4), Vec3(0.1, 1.6, 0.8)};
  const Vec3 x(0.2f, 0.0f, 0.1f), n(0, 1, 0);
  const glm::dvec3 a(light.v0), b(light.v1), c(light.v2);
  glm::dvec3 light_normal = glm::normalize(glm::cross(b - a, c - a));
  if (glm::dot(light_normal, glm::dvec3(x) - a) < 0) light_normal = -light_normal;
  const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
  const int k = 400;
  double exact = 0;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k - i; ++j)
      for (int upper = 0; upper < (j < k - i - 1 ? 2 : 1); ++upper) {
        // The centroids of the k^2 small triangles of a regular subdivision.
        const double u = (i + (upper ? 2.0 : 1.0) / 3.0) / k, v = (j + (upper ? 2.0 : 1.0) / 3.0) / k;
        const glm::dvec3 y = a + u * (b - a) + v * (c - a);
        const glm::dvec3 d = y - glm::dvec3(x);
        const double r2 = glm::dot(d, d);
        const double cos_x = std::max(0.0, glm::dot(glm::dvec3(n), d) / std::sqrt(r2));
        const double cos_y = std::max(0.0, glm::dot(light_normal, -d) / std::sqrt(r2));
        exact += cos_x * cos_y / r2 * area / (double(k) * k);
      }
  Rng rng(777, 0, 0);
  Mean estimate;
  for (int i = 0; i < 200000; ++i) {
    const EmitterSample s = RT_GRADED(light.sample)(x, rng.uniform2());
    estimate.add(s.pdf > 0 ? std::max(0.0f, glm::dot(n, s.wi)) / s.pdf : 0.0);
  }
  EXPECT_NEAR(estimate.mean(), exact, 4 * estimate.standard_error() + 1e-4 * exact);
  EXPECT_LT(estimate.standard_error(), 0.01 * exact);
}

}  // namespace
}  // namespace rt
