// Stage 4: the environment light. Its 1D and 2D piecewise-constant densities, checked by hand and
// by chi-square; the solid-angle density against the samples it describes (chi-square on bins of
// the sphere) and against the radiance it should follow; and direct lighting under it against
// closed forms: the white furnace, and a floor under a bright patch of sky.
#include "04-radiometry/direct_lighting.h"
#include "04-radiometry/environment_light.h"
#include "common/display_transform.h"
#include "common/spherical.h"
#include "direct_estimators.h"
#include "stage4/records.h"
#include "support/chi_square.h"
#include "support/sample_mean.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <memory>

namespace rt {
namespace {

TEST(PiecewiseConstant1D, SamplesAreExactBinaryFractions) {
  const std::vector<float> values{1.0f, 3.0f};
  const PiecewiseConstant1D d(values);
  EXPECT_FLOAT_EQ(d.integral(), 2.0f);
  // Bin 0 has probability 1/4: u = 1/8 is half-way through it.
  PiecewiseConstant1D::Sample s = RT_GRADED(d.sample)(0.125f);
  EXPECT_EQ(s.bin, 0);
  EXPECT_FLOAT_EQ(s.x, 0.25f);
  EXPECT_FLOAT_EQ(s.pdf, 0.5f);
  // u = 5/8 is half-way through bin 1's interval [1/4, 1).
  s = RT_GRADED(d.sample)(0.625f);
  EXPECT_EQ(s.bin, 1);
  EXPECT_FLOAT_EQ(s.x, 0.75f);
  EXPECT_FLOAT_EQ(s.pdf, 1.5f);
  EXPECT_FLOAT_EQ(RT_GRADED(d.pdf)(0.3f), 0.5f);
  EXPECT_FLOAT_EQ(RT_GRADED(d.pdf)(0.7f), 1.5f);
  EXPECT_EQ(RT_GRADED(d.pdf)(1.0f), 0.0f);
  EXPECT_EQ(RT_GRADED(d.pdf)(-0.1f), 0.0f);
  EXPECT_LT(RT_GRADED(d.sample)(0x1.fffffep-1f).x, 1.0f);
}

TEST(PiecewiseConstant1D, EmptyBinsAreNeverSampled) {
  const std::vector<float> values{0.0f, 1.0f, 0.0f, 1.0f};
  const PiecewiseConstant1D d(values);
  EXPECT_FLOAT_EQ(RT_GRADED(d.sample)(0.0f).x, 0.25f);
  EXPECT_FLOAT_EQ(RT_GRADED(d.sample)(0.5f).x, 0.75f);
  float last = -1.0f;
  for (int k = 0; k < 1000; ++k) {
    const PiecewiseConstant1D::Sample s = RT_GRADED(d.sample)(float(k) / 1000.0f);
    EXPECT_TRUE(s.bin == 1 || s.bin == 3);
    EXPECT_GT(s.pdf, 0.0f);
    EXPECT_GE(s.x, last) << "monotone in u";
    last = s.x;
  }
  const std::vector<float> zeros(5, 0.0f);
  EXPECT_FLOAT_EQ(RT_GRADED(PiecewiseConstant1D(zeros).sample)(0.3f).x, 0.3f) << "all zero: uniform";
}

TEST(PiecewiseConstant1D, ChiSquareAgainstItsDensity) {
  const std::vector<float> values{0.5f, 2.0f, 0.0f, 1.0f, 4.0f, 0.25f, 1.5f, 3.0f};
  const PiecewiseConstant1D d(values);
  constexpr int kSamples = 200000, kBins = 32;  // four bins of the test per bin of the density
  std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
  Rng rng(7, 0, 0);
  for (int k = 0; k < kSamples; ++k)
    observed[size_t(std::min(int(RT_GRADED(d.sample)(rng.uniform()).x * kBins), kBins - 1))] += 1.0;
  for (int b = 0; b < kBins; ++b) expected[size_t(b)] = kSamples * RT_GRADED(d.pdf)((b + 0.5f) / kBins) / kBins;
  const testing::ChiSquareResult r = testing::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed) << r.message;
}

// A latitude-longitude image with one bright block and a dim rest.
std::shared_ptr<const Image> peaked_map(int width, int height, int x0, int x1, int y0, int y1, Color bright,
                                        Color dim) {
  auto image = std::make_shared<Image>(width, height, dim);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) image->at(x, y) = bright;
  return image;
}

Environment environment_of(std::shared_ptr<const Image> image, float rotation = 0.0f) {
  Environment e;
  e.image = std::move(image);
  e.rotation_degrees = rotation;
  return e;
}

TEST(EnvironmentLight, DensityFollowsRadianceNotTexelCount) {
  // Every texel its own value; at each texel's centre direction p(w) / luminance(L(w)) must be
  // one number: the sin(theta) in the table and the 1 / sin(theta) of the Jacobian cancel there.
  auto image = std::make_shared<Image>(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) image->at(x, y) = Color(0.5f + float((x * 5 + y * 3) % 7), 1.0f, 0.25f);
  const EnvironmentLight light(environment_of(image, 30.0f));
  double ratio = 0.0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const Vec2 uv((x + 0.5f) / 8.0f, 1.0f - (y + 0.5f) / 4.0f);
      // The map's direction, turned by the rotation about +y (30 degrees).
      const Vec3 d = latlong_direction(uv);
      const float c = std::cos(radians(30.0f)), s = std::sin(radians(30.0f));
      const Vec3 w(d.x * c + d.z * s, d.y, -d.x * s + d.z * c);
      EXPECT_EQ(RT_GRADED(light.radiance)(w), image->at(x, y)) << "texel " << x << ", " << y;
      const double r = double(RT_GRADED(light.pdf)(w)) / double(luminance(RT_GRADED(light.radiance)(w)));
      if (ratio == 0.0) ratio = r;
      EXPECT_NEAR(r / ratio, 1.0, 1e-4) << "texel " << x << ", " << y;
    }
}

TEST(EnvironmentLight, SamplesMatchTheirDensityChiSquare) {
  // 16 x 8 texels, turned by 45 degrees (two texels), binned in 32 x 16 cells of the world's own
  // latitude-longitude map: every cell inside one texel, where p(s, t) is constant, so a cell
  // expects N p(w_centre) 2 pi^2 sin(theta_centre) / (32 x 16) samples.
  const EnvironmentLight light(
      environment_of(peaked_map(16, 8, 3, 6, 1, 3, Color(40.0f, 30.0f, 20.0f), Color(0.2f, 0.3f, 0.5f)), 45.0f));
  constexpr int kSamples = 400000, kColumns = 32, kRows = 16;
  std::vector<double> observed(kColumns * kRows, 0.0), expected(kColumns * kRows, 0.0);
  Rng rng(11, 0, 0);
  int consistent = 0;
  for (int k = 0; k < kSamples; ++k) {
    const std::optional<EnvironmentSample> s = RT_GRADED(light.sample)(rng.uniform2());
    ASSERT_TRUE(s.has_value());
    ASSERT_GT(s->pdf, 0.0f);
    const float pdf = RT_GRADED(light.pdf)(s->wi);
    if (std::abs(pdf - s->pdf) <= 1e-3f * s->pdf && s->radiance == RT_GRADED(light.radiance)(s->wi)) ++consistent;
    const Vec2 uv = latlong_uv(s->wi);
    const int column = std::min(int(uv.x * kColumns), kColumns - 1), row = std::min(int((1.0f - uv.y) * kRows), kRows - 1);
    observed[size_t(row * kColumns + column)] += 1.0;
  }
  // Away from texel borders, sample() and pdf() and radiance() must agree exactly enough.
  EXPECT_GT(consistent, kSamples * 99 / 100);
  double total = 0.0;
  for (int row = 0; row < kRows; ++row)
    for (int column = 0; column < kColumns; ++column) {
      const Vec2 uv((column + 0.5f) / kColumns, 1.0f - (row + 0.5f) / kRows);
      const float theta = kPi * (row + 0.5f) / kRows;
      const double p_st = double(RT_GRADED(light.pdf)(latlong_direction(uv))) * 2.0 * kPi * kPi * std::sin(theta);
      expected[size_t(row * kColumns + column)] = kSamples * p_st / (kColumns * kRows);
      total += p_st / (kColumns * kRows);
    }
  EXPECT_NEAR(total, 1.0, 1e-4) << "the density integrates to 1 over the sphere";
  const testing::ChiSquareResult r = testing::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(EnvironmentLight, PolesGiveNoSampleAndNoInfiniteDensity) {
  // At a pole sin(theta) = 0 and p(w) = p(s, t) / (2 pi^2 sin(theta)) is infinite: sample() must
  // give no direction there (u.y = 0 picks the first row at t = 0) and pdf() must give 0, never
  // an infinite weight that would turn a pixel NaN.
  const EnvironmentLight light(environment_of(peaked_map(16, 8, 3, 6, 0, 2, Color(40.0f), Color(0.5f))));
  for (const float ux : {0.0f, 0.3f, 0.9f}) EXPECT_FALSE(RT_GRADED(light.sample)(Vec2(ux, 0.0f)).has_value()) << ux;
  EXPECT_EQ(RT_GRADED(light.pdf)(Vec3(0.0f, 1.0f, 0.0f)), 0.0f);
  EXPECT_EQ(RT_GRADED(light.pdf)(Vec3(0.0f, -1.0f, 0.0f)), 0.0f);
  // Just off the pole both are finite and agree.
  const std::optional<EnvironmentSample> near = RT_GRADED(light.sample)(Vec2(0.3f, 1e-4f));
  ASSERT_TRUE(near.has_value());
  EXPECT_TRUE(std::isfinite(near->pdf));
  EXPECT_NEAR(RT_GRADED(light.pdf)(near->wi), near->pdf, 1e-2f * near->pdf);
}

TEST(EnvironmentLight, ConstantEnvironmentIsUniformOnTheSphere) {
  Environment e;
  e.scale = Color(2.0f, 1.0f, 0.5f);
  const EnvironmentLight light(e);
  EXPECT_TRUE(light.constant());
  Rng rng(3, 0, 0);
  for (int k = 0; k < 100; ++k) {
    const std::optional<EnvironmentSample> s = RT_GRADED(light.sample)(rng.uniform2());
    ASSERT_TRUE(s.has_value());
    EXPECT_FLOAT_EQ(s->pdf, 0.25f * kInvPi);
    EXPECT_EQ(s->radiance, e.scale);
    EXPECT_NEAR(glm::length(s->wi), 1.0f, 1e-5f);
  }
  // Its power through a disk of radius r: pi r^2 x 4 pi x luminance.
  EXPECT_NEAR(light.power(2.0f), kPi * 4.0f * 4.0f * kPi * luminance(e.scale), 1e-3f);
}

using testing::Estimate;
using testing::estimator_name;
using testing::kEstimators;

// Direct lighting at one fixed point under an environment: `samples` estimates, mean and error.
Estimate estimate(const LightingScene& scene, const Ray& ray, DirectEstimator estimator, int samples, int channel = 0) {
  DirectOptions options;
  options.estimator = estimator;
  return testing::subject([&] {
    testing::SampleMean m;
    for (int k = 0; k < samples; ++k) {
      Rng rng(5, 0, std::uint64_t(k));
      m.add(direct_radiance(scene, ray, options, rng)[channel]);
    }
    return m.estimate();
  });
}

SceneDescription sphere_under(Environment environment, float albedo = 1.0f) {
  SceneDescription d;
  d.source = "furnace";
  Material ball;
  ball.albedo = Color(albedo);
  d.materials.push_back(ball);
  d.shapes.push_back(Shape{"ball", Sphere{Vec3(0.0f), 1.0f}, 0});
  d.environment = std::move(environment);
  return d;
}

// The white furnace: a Lambertian sphere of albedo rho under an environment of radiance 1
// everywhere reflects exactly rho (it sees no part of itself, and rho E / pi = rho pi / pi). Once
// with the constant environment, once with an image of 1s that goes through the table and its
// Jacobian. Every ray must hit the ball: one that missed would see the environment's 1 as well.
TEST(EnvironmentFurnace, LambertianSphereReturnsItsAlbedoForEveryEstimator) {
  Environment constant;
  constant.scale = Color(1.0f);
  const Environment image = environment_of(std::make_shared<Image>(32, 16, Color(1.0f)), 10.0f);
  for (const float rho : {1.0f, 0.5f})
    for (const Environment& e : {constant, image}) {
      const LightingScene scene(sphere_under(e, rho));
      for (const Vec3 target : {Vec3(0, 1, 0), Vec3(0.6f, 0, 0.8f), Vec3(0, -1, 0)}) {
        const Ray ray{target * 3.0f, -target};
        ASSERT_TRUE(RT_GRADED(scene.closest_hit)(ray, Interval::positive()).has_value()) << "the ray must hit the ball";
        for (const DirectEstimator estimator : kEstimators) {
          const Estimate m = estimate(scene, ray, estimator, 20000);
          EXPECT_NEAR(m.mean, rho, 4.0 * m.standard_error + 1e-6)
              << "estimator " << estimator_name(estimator) << (e.image ? " image" : " constant") << ", rho " << rho << ", at "
              << target.x << "," << target.y << "," << target.z << ": +- " << m.standard_error;
          EXPECT_LT(m.standard_error, 0.02);
        }
      }
    }
}

// A floor (albedo 1/2, normal +y) under a sky that is black but for one block of texels of
// radiance L: rows 2-3 of 16 (theta from 22.5 to 45 degrees) and columns 4-7 of 32 (phi from 45
// to 90 degrees). Its irradiance has a closed form,
//     E = L integral_phi0^phi1 integral_theta0^theta1 cos(theta) sin(theta) dtheta dphi
//       = L (phi1 - phi0) (sin^2 theta1 - sin^2 theta0) / 2,
// and the floor sends back rho E / pi.
class BrightPatch : public ::testing::Test {
 protected:
  static constexpr float kL = 50.0f, kRho = 0.5f;
  static SceneDescription description(float dim = 0.0f) {
    SceneDescription d;
    d.source = "patch";
    Material floor;
    floor.albedo = Color(kRho);
    d.materials.push_back(floor);
    d.shapes.push_back(Shape{"floor", Quad{{Vec3(-10, 0, -10), Vec3(-10, 0, 10), Vec3(10, 0, 10), Vec3(10, 0, -10)}}, 0});
    d.environment = environment_of(peaked_map(32, 16, 4, 8, 2, 4, Color(kL), Color(dim)));
    return d;
  }
  static double closed_form() {
    const double phi = kPi / 4.0, s1 = std::sin(kPi / 4.0), s0 = std::sin(kPi / 8.0);
    return kRho / kPi * kL * phi * (s1 * s1 - s0 * s0) / 2.0;
  }
  const Ray ray{Vec3(2.0f, 1.0f, 0.5f), glm::normalize(Vec3(-2.0f, -1.0f, -0.5f))};
};

TEST_F(BrightPatch, EveryEstimatorFindsTheClosedFormIrradiance) {
  const LightingScene scene(description());
  ASSERT_TRUE(RT_GRADED(scene.closest_hit)(ray, Interval::positive()).has_value()) << "the ray must hit the floor";
  for (const DirectEstimator estimator : kEstimators) {
    const Estimate m = estimate(scene, ray, estimator, 40000);
    EXPECT_NEAR(m.mean, closed_form(), 4.0 * m.standard_error) << "estimator " << estimator_name(estimator) << ": +- " << m.standard_error;
    EXPECT_LT(m.standard_error, 0.05 * closed_form()) << "estimator " << estimator_name(estimator);
  }
}

TEST_F(BrightPatch, ImportanceSamplingBeatsUniformByAMeasuredFactor) {
  // Light sampling both ways; their variances per sample compared (docs/stage4.md charts the
  // factor). The patch holds 1.4 % of the sphere, so a uniform direction finds it 1 time in 70.
  LightingOptions uniform;
  uniform.environment_sampling = EnvironmentSampling::uniform;
  const Estimate by_table = estimate(LightingScene(description(0.01f)), ray, DirectEstimator::light, 20000);
  const Estimate by_sphere = estimate(LightingScene(description(0.01f), uniform), ray, DirectEstimator::light, 20000);
  EXPECT_NEAR(by_table.mean, by_sphere.mean, 4.0 * std::hypot(by_table.standard_error, by_sphere.standard_error));
  const double factor = (by_sphere.standard_error * by_sphere.standard_error) / (by_table.standard_error * by_table.standard_error);
  EXPECT_GT(factor, 20.0) << "variance ratio uniform / importance";
}

TEST(EnvironmentScene, ChosenAgainstAreaEmittersByPower) {
  SceneDescription d = sphere_under(Environment{});
  d.environment->scale = Color(1.0f);
  Material lamp;
  lamp.emission = Color(10.0f);
  d.materials.push_back(lamp);
  d.shapes.push_back(Shape{"lamp", Disk{Vec3(0, 3, 0), Vec3(0, -1, 0), 0.5f}, 1});
  const LightingScene scene(d);
  ASSERT_EQ(scene.environment_index(), 1);
  // Powers: the disk pi x 10 x pi 0.25; the environment pi r^2 x 4 pi x 1 with r the bounding
  // sphere's radius, half the diagonal of the box around the ball and the disk: (2, 4, 2).
  const float disk = kPi * 10.0f * kPi * 0.25f;
  const float p_env = scene.emitter_distribution().pmf(1);
  const float environment = disk * p_env / (1.0f - p_env);
  const float radius = std::sqrt(environment / (4.0f * kPi * kPi));
  EXPECT_NEAR(radius, 0.5f * glm::length(Vec3(2.0f, 4.0f, 2.0f)), 1e-3f);
}

}  // namespace
}  // namespace rt
