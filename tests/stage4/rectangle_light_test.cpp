// Stage 4: a rectangle light sampled by the solid angle it subtends (Urena, Fajardo & King 2013)
// and by area. Checked against answers computed another way: the solid angle of each piece of the
// rectangle by Van Oosterom & Strackee's triangle formula (in double), and the irradiance by
// Lambert's polygon formula.
#include "04-radiometry/emitters.h"
#include "04-radiometry/lighting_scene.h"
#include "04-radiometry/radiometry.h"
#include "04-radiometry/spherical_rectangle.h"
#include "support/chi_square.h"
#include "emitter_estimates.h"
#include "common/random.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

// Van Oosterom & Strackee, "The Solid Angle of a Plane Triangle", IEEE Trans. Biomed. Eng. 30(2),
// 1983: tan(Omega / 2) = |a . (b x c)| / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|).
double triangle_solid_angle(DVec3 a, DVec3 b, DVec3 c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

// The solid angle, seen from x, of the part [s0, s1] x [t0, t1] of corner + s eu + t ev.
double part_solid_angle(const RectangleEmitter& r, Vec3 x, double s0, double s1, double t0, double t1) {
  auto p = [&](double s, double t) { return DVec3(r.corner) + s * DVec3(r.edge_u) + t * DVec3(r.edge_v) - DVec3(x); };
  return triangle_solid_angle(p(s0, t0), p(s1, t0), p(s1, t1)) + triangle_solid_angle(p(s0, t0), p(s1, t1), p(s0, t1));
}

std::vector<Vec3> corners(const RectangleEmitter& r) {
  return {r.corner, r.corner + r.edge_u, r.corner + r.edge_u + r.edge_v, r.corner + r.edge_v};
}

// A 2 x 1.5 rectangle 0.25 above x and off to one side, facing down (towards x).
const RectangleEmitter kNear{Vec3(-1.0f, 0.25f, -0.5f), Vec3(2, 0, 0), Vec3(0, 0, 1.5f), RectangleSampling::solid_angle};
const Vec3 kBelow(0.3f, 0.0f, 0.2f);

TEST(SphericalRectangle, SolidAngleMatchesTwoTriangles) {
  // Random rectangles seen from random points, near their plane and up to 30 units away, down to
  // kMinSolidAngle: S within 2e-6 sr (x's coordinates in the rectangle's frame are floats), a
  // relative 2e-4 at the threshold and far less for nearer lights.
  Rng rng(41, 0, 0);
  int checked = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3 eu = 2.0f * Vec3(rng.uniform() + 0.05f, 0.0f, 0.0f), ev = Vec3(0.0f, rng.uniform() + 0.05f, 0.0f);
    const Vec3 corner(rng.uniform() - 1.0f, rng.uniform() - 1.0f, 0.0f);
    // Any side of the plane, near and far (up to 30 units).
    const float distance = std::pow(3000.0f, rng.uniform()) * (rng.uniform() < 0.5f ? -0.01f : 0.01f);
    const Vec3 x(4.0f * rng.uniform() - 2.0f, 4.0f * rng.uniform() - 2.0f, distance);
    const RectangleEmitter r{corner, eu, ev};
    const double exact = part_solid_angle(r, x, 0, 1, 0, 1);
    const float s = SphericalRectangle(x, corner, eu, ev).solid_angle();
    if (exact < RectangleEmitter::kMinSolidAngle) continue;
    ++checked;
    ASSERT_NEAR(s, exact, 2e-6) << "x = " << x.x << " " << x.y << " " << x.z;
    if (exact > 0.5) {
      ASSERT_NEAR(s, exact, 1e-5 * exact);
    }
  }
  EXPECT_GT(checked, 1000);
  // The cube face from the cube's centre: 4 pi / 6.
  EXPECT_NEAR(SphericalRectangle(Vec3(0.0f), Vec3(-1, -1, 1), Vec3(2, 0, 0), Vec3(0, 2, 0)).solid_angle(),
              4.0 * testing::kPiD / 6.0, 1e-6);
}

TEST(RectangleChiSquare, SolidAngleSamplingIsUniformOverTheSubtendedDirections) {
  // Bin the sampled points by where they land on the rectangle; a bin's share is its own solid
  // angle over the whole one's. A sampler uniform in AREA, or one that forgot the column's
  // sine-of-elevation warp, puts visibly more points in the far corners.
  for (const Vec3 x : {kBelow, Vec3(-1.5f, -0.1f, 1.9f), Vec3(0.9f, 0.2f, 0.9f)}) {
    constexpr int kBins = 16, kSamples = 400000;
    std::vector<double> observed(kBins * kBins, 0.0), expected(kBins * kBins);
    const double total = part_solid_angle(kNear, x, 0, 1, 0, 1);
    for (int i = 0; i < kBins; ++i)
      for (int j = 0; j < kBins; ++j)
        expected[size_t(i * kBins + j)] =
            kSamples * part_solid_angle(kNear, x, double(i) / kBins, double(i + 1) / kBins, double(j) / kBins,
                                        double(j + 1) / kBins) / total;
    Rng rng(42, 0, 0);
    for (int k = 0; k < kSamples; ++k) {
      const EmitterSample s = kNear.sample(x, rng.uniform2());
      ASSERT_NEAR(s.pdf, 1.0 / total, 1e-5 / total);
      const Vec3 local = s.point - kNear.corner;
      const double u = glm::dot(local, kNear.edge_u) / glm::dot(kNear.edge_u, kNear.edge_u);
      const double v = glm::dot(local, kNear.edge_v) / glm::dot(kNear.edge_v, kNear.edge_v);
      ASSERT_NEAR(glm::dot(local, glm::cross(kNear.edge_u, kNear.edge_v)), 0.0f, 1e-5f);  // on the plane
      ASSERT_TRUE(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0) << u << " " << v;
      observed[size_t(std::min(kBins - 1, int(u * kBins)) * kBins + std::min(kBins - 1, int(v * kBins)))] += 1.0;
    }
    const auto r = testing::chi_square_test(observed, expected);
    EXPECT_TRUE(r.passed) << r.message;
  }
}

// E[cos(theta_x) / p] = the projected solid angle, which Lambert's formula gives exactly.
testing::Estimate projected_solid_angle(const RectangleEmitter& r, Vec3 x, Vec3 n, int samples, std::uint64_t seed) {
  const AreaEmitter e{r, Color(1.0f)};
  return testing::mean_of(samples, seed, [&](Rng& rng) { return testing::projected_solid_angle_sample(e, x, n, rng.uniform2()); });
}

TEST(RectangleLight, BothStrategiesReproduceLambertsFormulaNearAndFar) {
  // The receivers' normals keep the whole light above their horizon: Lambert's formula integrates
  // the cosine unclipped.
  struct Case {
    Vec3 x, n;
    const char* where;
  };
  // Near (0.02 below the light), at a middle distance, and far enough that the solid angle is
  // under kMinSolidAngle (area sampling then serves both strategies).
  const Vec3 tilted = glm::normalize(Vec3(0.05f, 1.0f, 0.05f));
  for (const Case c : {Case{Vec3(0.4f, 0.23f, 0.1f), Vec3(0, 1, 0), "near"}, Case{kBelow, tilted, "middle"},
                       Case{Vec3(1.0f, -20.0f, 3.0f), tilted, "far"}}) {
    const double exact = RT_GRADED(polygon_irradiance)(c.x, c.n, corners(kNear), 1.0f);
    for (const RectangleSampling strategy : {RectangleSampling::area, RectangleSampling::solid_angle}) {
      RectangleEmitter r = kNear;
      r.strategy = strategy;
      const testing::Estimate m = projected_solid_angle(r, c.x, c.n, 200000, 43);
      EXPECT_NEAR(m.mean, exact, 4.0 * m.standard_error + 1e-4 * exact) << c.where;
      // Area sampling right under a large light is the case solid angle exists for.
      if (strategy == RectangleSampling::solid_angle || std::string(c.where) != "near") {
        EXPECT_LT(m.standard_error, 0.02 * exact) << c.where;
      }
    }
  }
  EXPECT_LT(part_solid_angle(kNear, Vec3(1.0f, -20.0f, 3.0f), 0, 1, 0, 1), RectangleEmitter::kMinSolidAngle);
}

TEST(RectangleLight, SolidAngleSamplingRemovesTheVarianceNearTheLight) {
  // 0.02 below a 2 x 1.5 light, area sampling's 1/r^2 spans four orders of magnitude; solid-angle
  // sampling leaves only the cosine at x to vary.
  const Vec3 x(0.4f, 0.23f, 0.1f), n(0, 1, 0);
  RectangleEmitter by_area = kNear;
  by_area.strategy = RectangleSampling::area;
  const testing::Estimate area = projected_solid_angle(by_area, x, n, 100000, 44);
  const testing::Estimate solid = projected_solid_angle(kNear, x, n, 100000, 44);
  EXPECT_LT(solid.standard_error * 5.0, area.standard_error)
      << "area " << area.standard_error << ", solid angle " << solid.standard_error;
}

TEST(RectangleLight, PdfAgreesWithSampleAndNothingComesFromBehind) {
  for (const RectangleSampling strategy : {RectangleSampling::area, RectangleSampling::solid_angle}) {
    RectangleEmitter r = kNear;
    r.strategy = strategy;
    Rng rng(45, 0, 0);
    for (const Vec3 x : {kBelow, Vec3(0.4f, 0.23f, 0.1f), Vec3(1.0f, -20.0f, 3.0f)})
      for (int k = 0; k < 1000; ++k) {
        const EmitterSample s = r.sample(x, rng.uniform2());
        ASSERT_GT(s.pdf, 0.0f);
        EXPECT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::length(s.point - x), s.distance, 1e-4f * s.distance);
        EXPECT_NEAR(r.pdf(x, s.point), s.pdf, 1e-3f * s.pdf);
      }
    // Behind the emitting side, and in its plane: no sample, density 0.
    for (const Vec3 x : {Vec3(0.0f, 0.5f, 0.0f), Vec3(3.0f, 0.25f, 0.0f)}) {
      EXPECT_EQ(r.sample(x, Vec2(0.5f)).pdf, 0.0f);
      EXPECT_EQ(r.pdf(x, Vec3(0.0f, 0.25f, 0.0f)), 0.0f);
    }
  }
}

TEST(LightingScene, OnlyRectangularQuadsBecomeOneRectangleEmitter) {
  const std::string head = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"light": {"emission": [1, 1, 1]}}, "shapes": [{"type": "quad", "material": "light", "vertices": )";
  auto emitters = [&](const char* vertices, LightingOptions options = {}) {
    return LightingScene(parse_scene(head + vertices + "}]}", "quad.json"), options).emitters();
  };
  // The Cornell box's light, a rectangle in any orientation.
  const auto cornell = emitters("[[343, 548.7, 227], [343, 548.7, 332], [213, 548.7, 332], [213, 548.7, 227]]");
  ASSERT_EQ(cornell.size(), 1u);
  const auto& r = std::get<RectangleEmitter>(cornell[0].geometry);
  EXPECT_EQ(r.strategy, RectangleSampling::area);
  EXPECT_NEAR(r.area(), 130.0f * 105.0f, 1e-2f);
  EXPECT_NEAR(r.normal().y, -1.0f, 1e-6f);  // the front of its triangles, (v1 - v0) x (v2 - v0)
  EXPECT_EQ(emitters("[[0, 0, 0], [1, 1, 0], [0, 2, 0], [-1, 1, 0]]").size(), 1u);  // tilted 45 degrees
  // A parallelogram that is not a rectangle, and a trapezoid: two triangles each.
  EXPECT_EQ(emitters("[[0, 0, 0], [1, 0, 0], [1.5, 1, 0], [0.5, 1, 0]]").size(), 2u);
  EXPECT_EQ(emitters("[[0, 0, 0], [2, 0, 0], [1.5, 1, 0], [0.5, 1, 0]]").size(), 2u);
  LightingOptions by_solid_angle;
  by_solid_angle.rectangle_sampling = RectangleSampling::solid_angle;
  EXPECT_EQ(std::get<RectangleEmitter>(emitters("[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]", by_solid_angle)[0].geometry).strategy,
            RectangleSampling::solid_angle);
}

}  // namespace
}  // namespace rt
