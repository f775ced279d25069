// Stage 4: radiometry helpers, choosing emitters by power, and emitter sampling. Every sampler is
// checked for unbiasedness against closed forms: E[1 / p(w)] is the solid angle the emitter
// subtends, and E[cos(theta) / p(w)] its projected solid angle, which Lambert's polygon formula and
// the configuration factors of closed_form.h give exactly.
#include "03-acceleration/bvh_aggregate.h"
#include "04-radiometry/discrete_distribution.h"
#include "04-radiometry/emitters.h"
#include "04-radiometry/lighting_scene.h"
#include "04-radiometry/radiometry.h"
#include "support/chi_square.h"
#include "common/error.h"
#include "common/frame.h"
#include "common/random.h"
#include "closed_form.h"
#include "emitter_estimates.h"
#include "stage3/records.h"
#include "stage4/records.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

TEST(Radiometry, SolidAngleOfTheHemisphereIsTwoPi) {
  // dw = sin(theta) dtheta dphi.
  const double omega = testing::integrate_2d([](double t, double) { return std::sin(t); }, 0.0, 0.5 * kPi, 0.0, 2.0 * kPi, 64);
  EXPECT_NEAR(omega, 2.0 * kPi, 1e-6);
  EXPECT_NEAR(cone_solid_angle(0.0f), 2.0f * kPi, 1e-6f);
  EXPECT_NEAR(cone_solid_angle(-1.0f), 4.0f * kPi, 1e-5f);
}

TEST(Radiometry, AreaToSolidAngle) {
  // A patch of area dA at distance 2, tilted 60 degrees: dw = dA cos / r^2 = dA / 8, so a density
  // of 1 per unit area is 8 per steradian.
  EXPECT_FLOAT_EQ(RT_GRADED(area_to_solid_angle_pdf)(1.0f, 2.0f, 0.5f), 8.0f);
  EXPECT_FLOAT_EQ(RT_GRADED(area_to_solid_angle_pdf)(0.25f, 2.0f, -0.5f), 2.0f);  // either side
  EXPECT_TRUE(std::isinf(RT_GRADED(area_to_solid_angle_pdf)(1.0f, 2.0f, 0.0f)));
}

TEST(Radiometry, PointLightIrradianceAndLambertianRadiance) {
  // I = 1 at r = 2 and 60 degrees: E = I cos / r^2 = 0.125.
  EXPECT_FLOAT_EQ(point_light_irradiance(Color(1.0f), 2.0f, 0.5f).x, 0.125f);
  EXPECT_EQ(point_light_irradiance(Color(1.0f), 2.0f, -0.5f), Color(0.0f));
  EXPECT_FLOAT_EQ(lambertian_radiance(Color(0.5f), Color(kPi)).x, 0.5f);
  EXPECT_FLOAT_EQ(lambertian_emitter_flux(Color(1.0f), 2.0f).x, 2.0f * kPi);
  EXPECT_FLOAT_EQ(point_light_flux(Color(1.0f)).x, 4.0f * kPi);
  EXPECT_NEAR(luminance(Color(1.0f)), 1.0f, 1e-6f);
}

TEST(Radiometry, PolygonIrradianceMatchesTheConfigurationFactors) {
  const Vec3 p(0.0f), n(0, 0, 1);
  // A unit square with a corner above p at height 1 (Siegel & Howell): E = pi L F.
  const std::vector<Vec3> corner{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  EXPECT_NEAR(RT_GRADED(polygon_irradiance)(p, n, corner, 1.0f), kPi * testing::factor_to_corner_rectangle(1, 1, 1),
              1e-6);
  EXPECT_NEAR(RT_GRADED(polygon_irradiance)(p, n, corner, 1.0f), 0.435210, 1e-6);
  // A 2 x 2 square centred above, wound either way.
  const std::vector<Vec3> centred{{-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}};
  EXPECT_NEAR(RT_GRADED(polygon_irradiance)(p, n, centred, 1.0f), kPi * testing::factor_to_centred_square(2, 1), 1e-5);
  EXPECT_NEAR(RT_GRADED(polygon_irradiance)(p, n, centred, 1.0f), 1.740840, 1e-5);
  // The triangle (0,0,1) (1,0,1) (0,1,1) from the origin.
  EXPECT_NEAR(RT_GRADED(polygon_irradiance)(p, n, std::vector<Vec3>{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, 1.0f), 0.302300,
              1e-6);
  // Far away it becomes a point source: E -> L A cos / r^2.
  const std::vector<Vec3> far{{-0.01f, -0.01f, 100}, {0.01f, -0.01f, 100}, {0.01f, 0.01f, 100}, {-0.01f, 0.01f, 100}};
  EXPECT_NEAR(RT_GRADED(polygon_irradiance)(p, n, far, 1.0f), 4e-4 / 1e4, 1e-12);
}

TEST(DiscreteDistribution, ChoosesInProportionToWeight) {
  const std::vector<float> weights{1.0f, 0.0f, 3.0f, 0.5f, 0.0f, 5.5f};
  const DiscreteDistribution d(weights);
  EXPECT_FLOAT_EQ(d.pmf(0), 0.1f);
  EXPECT_FLOAT_EQ(d.pmf(1), 0.0f);
  EXPECT_FLOAT_EQ(d.pmf(5), 0.55f);
  EXPECT_EQ(d.pmf(6), 0.0f);
  constexpr int kN = 1000000;
  std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
  Rng rng(21, 0, 0);
  for (int k = 0; k < kN; ++k) {
    const auto choice = RT_GRADED(d.sample)(rng.uniform());
    ASSERT_FLOAT_EQ(choice.pmf, d.pmf(choice.index));
    observed[size_t(choice.index)] += 1.0;
  }
  for (size_t i = 0; i < weights.size(); ++i) expected[i] = kN * double(d.pmf(int(i)));
  const auto r = testing::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed) << r.message;
  // The ends of [0, 1): never a zero-weight item.
  EXPECT_EQ(RT_GRADED(d.sample)(0.0f).index, 0);
  EXPECT_EQ(RT_GRADED(d.sample)(1.0f - 0x1p-24f).index, 5);
  EXPECT_EQ(RT_GRADED(d.sample)(0.1f).index, 2);  // exactly at the boundary after the zero-weight item
}

using testing::Estimate;
using testing::mean_of;
using testing::projected_solid_angle_sample;

TEST(EmitterSampling, TriangleReproducesLambertsFormula) {
  const Vec3 x(0.1f, -0.2f, 0.0f), n = glm::normalize(Vec3(0.2f, 0.1f, 1.0f));
  // Facing down, towards x.
  const AreaEmitter e{TriangleEmitter{Vec3(-0.5f, 0, 1), Vec3(0.3f, 0.9f, 1.2f), Vec3(0.8f, -0.4f, 0.9f)}, Color(1.0f)};
  const Estimate m = mean_of(200000, 22, [&](Rng& rng) { return projected_solid_angle_sample(e, x, n, rng.uniform2()); });
  const auto& t = std::get<TriangleEmitter>(e.geometry);
  const double exact = RT_GRADED(polygon_irradiance)(x, n, std::vector<Vec3>{t.v0, t.v1, t.v2}, 1.0f);
  EXPECT_NEAR(m.mean, exact, 4.0 * m.standard_error);
  EXPECT_LT(m.standard_error, 0.01 * exact);
}

TEST(EmitterSampling, QuadLightIsTwoTrianglesChosenByArea) {
  // A quad (concave at its third corner) whose triangles differ in area, 2.25 and 3.75: a quad light
  // that picks its halves with equal probability, or samples one of them only, misses Lambert's value.
  const char* json = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"light": {"emission": [2, 2, 2]}, "white": {}},
    "shapes": [{"type": "quad", "material": "light",
                "vertices": [[-1, 1, -1], [2, 1, -1], [0.5, 1, 0.5], [-1, 1, 4]]}]})";
  const LightingScene scene(parse_scene(json, "kite.json"));
  ASSERT_EQ(scene.emitters().size(), 2u);
  const float a0 = scene.emitters()[0].area(), a1 = scene.emitters()[1].area();
  EXPECT_NEAR(scene.emitter_distribution().pmf(0), a0 / (a0 + a1), 1e-6);
  const Vec3 x(0.2f, 0.0f, 0.1f), n(0, 1, 0);
  const Estimate m = mean_of(400000, 23, [&](Rng& rng) {
    const auto choice = scene.emitter_distribution().sample(rng.uniform());
    const AreaEmitter& e = scene.emitters()[size_t(choice.index)];
    return 2.0 * projected_solid_angle_sample(e, x, n, rng.uniform2()) / choice.pmf;
  });
  const std::vector<Vec3> quad{{-1, 1, -1}, {2, 1, -1}, {0.5f, 1, 0.5f}, {-1, 1, 4}};
  const double exact = RT_GRADED(polygon_irradiance)(x, n, quad, 2.0f);
  EXPECT_NEAR(m.mean, exact, 4.0 * m.standard_error);
  EXPECT_LT(m.standard_error, 0.01 * exact);
}

TEST(EmitterSampling, DiskMatchesTheCoaxialFactor) {
  const AreaEmitter e{DiskEmitter{Vec3(0, 2, 0), Vec3(0, -1, 0), 0.5f}, Color(1.0f)};
  const Vec3 x(0.0f), n(0, 1, 0);
  const Estimate m = mean_of(200000, 24, [&](Rng& rng) { return projected_solid_angle_sample(e, x, n, rng.uniform2()); });
  EXPECT_NEAR(m.mean, kPi * testing::factor_to_coaxial_disk(0.5, 2.0), 4.0 * m.standard_error);
  EXPECT_NEAR(m.mean, 0.184800, 4.0 * m.standard_error);
}

TEST(EmitterSampling, SphereByConeAndByAreaMatchTheFactor) {
  // Sphere r = 1 at distance 2, receiver tilted 30 degrees: E = pi (r/d)^2 cos 30 = 0.680175.
  const Vec3 x(0.0f), n(std::sin(radians(30.0f)), std::cos(radians(30.0f)), 0.0f);
  for (const SphereSampling strategy : {SphereSampling::cone, SphereSampling::area}) {
    const AreaEmitter e{SphereEmitter{Vec3(0, 2, 0), 1.0f, strategy}, Color(1.0f)};
    const Estimate m = mean_of(200000, 25, [&](Rng& rng) { return projected_solid_angle_sample(e, x, n, rng.uniform2()); });
    EXPECT_NEAR(m.mean, kPi * testing::factor_to_sphere_on_normal(1.0, 2.0) * std::cos(radians(30.0f)),
                4.0 * m.standard_error);
    EXPECT_NEAR(m.mean, 0.680175, 4.0 * m.standard_error);
    // The cone wastes nothing: its only variance is the cosine's.
    if (strategy == SphereSampling::cone) {
      EXPECT_LT(m.standard_error, 0.001);
    }
  }
}

TEST(EmitterSampling, SolidAngleAndPdfAgree) {
  // E[1 / p] over front-facing samples is the solid angle the emitter covers; pdf() at the
  // sampled point equals the sample's density.
  const Vec3 x(0.3f, 0.0f, -0.2f);
  const Vec3 to_center = Vec3(0, 3, 0) - x;
  const double cone = 2.0 * kPi * (1.0 - std::sqrt(1.0 - 1.0 / double(glm::dot(to_center, to_center))));
  const std::vector<std::pair<AreaEmitter, double>> cases{
      {AreaEmitter{SphereEmitter{Vec3(0, 3, 0), 1.0f, SphereSampling::cone}, Color(1)}, cone},
      {AreaEmitter{SphereEmitter{Vec3(0, 3, 0), 1.0f, SphereSampling::area}, Color(1)}, -1.0},
      {AreaEmitter{DiskEmitter{Vec3(0, 1, 0), Vec3(0, -1, 0), 0.7f}, Color(1)}, -1.0},
      {AreaEmitter{TriangleEmitter{Vec3(-1, 1, -1), Vec3(1, 1, -1), Vec3(0, 1, 1)}, Color(1)}, -1.0}};
  for (const auto& [e, exact] : cases) {
    Rng rng(26, 0, 0);
    for (int k = 0; k < 1000; ++k) {
      const EmitterSample s = RT_GRADED(e.sample)(x, rng.uniform2());
      EXPECT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
      EXPECT_NEAR(glm::length(s.point - x), s.distance, 1e-4f * s.distance);
      EXPECT_NEAR(RT_GRADED(e.pdf)(x, s.point), s.pdf, 2e-3f * s.pdf);
    }
    if (exact > 0.0) {
      const Estimate m = mean_of(100000, 27, [&](Rng& r) {
        const EmitterSample s = RT_GRADED(e.sample)(x, r.uniform2());
        return e.radiance_towards(s.point, x) == Color(0.0f) ? 0.0 : 1.0 / s.pdf;
      });
      EXPECT_NEAR(m.mean, exact, 1e-4 * exact + 4.0 * m.standard_error);
    }
  }
}

TEST(EmitterSampling, ConeSamplesLieOnTheSphereFacingTheShadingPoint) {
  // The cone gives a direction; the sample's point is where that direction first meets the
  // sphere (the nearer root), so it lies on the sphere, on the cap that x sees. Only the
  // direction enters the irradiance, so the tests above cannot see a wrong point; a shadow ray
  // aimed at it would.
  const Vec3 center(0, 3, 0);
  const float radius = 1.0f;
  const AreaEmitter e{SphereEmitter{center, radius, SphereSampling::cone}, Color(1)};
  Rng rng(29, 0, 0);
  for (const Vec3 x : {Vec3(0.0f), Vec3(0.3f, 0.0f, -0.2f), Vec3(4.0f, -1.0f, 2.0f)}) {
    for (int k = 0; k < 1000; ++k) {
      const EmitterSample s = RT_GRADED(e.sample)(x, rng.uniform2());
      ASSERT_NEAR(glm::length(s.point - center), radius, 1e-4f) << "sample " << k << " is not on the sphere";
      ASSERT_GE(glm::dot(s.point - center, x - s.point), -1e-4f) << "sample " << k << " is on the far side";
    }
  }
}

TEST(LightingSceneErrors, RefusesWhatStageFourCannotRender) {
  const std::string head = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 40}, "materials": )";
  try {
    LightingScene(parse_scene(head + R"({"sky": {"emission": [1, 1, 1]}}, "shapes": [{"type": "plane", "material": "sky",
      "point": [0, 5, 0], "normal": [0, -1, 0]}]})", "sky.json"));
    FAIL() << "an emitting plane was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sky.json: /shapes/0: an emitting plane"), std::string::npos) << e.what();
  }
  try {
    LightingScene(parse_scene(head + R"({"shiny": {"specular": [0.5, 0.5, 0.5]}}, "shapes": []})", "shiny.json"));
    FAIL() << "a Blinn-Phong highlight was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shiny.json: /materials/shiny: stage 4 renders diffuse materials as Lambertian"),
              std::string::npos)
        << e.what();
  }
}

TEST(LightingScene, FindsDisksAndNamesEmitters) {
  const char* json = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"light": {"emission": [1, 1, 1]}, "white": {}},
    "shapes": [{"type": "sphere", "material": "white", "center": [0, -10, 0], "radius": 1},
               {"type": "disk", "material": "light", "center": [0, 1, 0], "normal": [0, -1, 0], "radius": 0.5},
               {"type": "quad", "material": "light", "vertices": [[-1, 3, -1], [-1, 3, 1], [1, 3, 1], [1, 3, -1]]}]})";
  const LightingScene scene(parse_scene(json, "disk.json"));
  ASSERT_EQ(scene.emitters().size(), 2u);  // the disk, and the square quad as one rectangle
  const auto up = RT_GRADED(scene.closest_hit)(Ray{Vec3(0.1f, 0, 0), Vec3(0, 1, 0)}, Interval::positive());
  ASSERT_TRUE(up);
  EXPECT_EQ(up->primitive, 1);
  EXPECT_NEAR(up->t, 1.0f, 1e-6f);
  EXPECT_TRUE(up->front_face);  // the disk faces down, towards the ray's origin
  EXPECT_EQ(RT_GRADED(scene.emitted)(*up), Color(1.0f));
  EXPECT_EQ(scene.emitter_index(*up), 0);
  const auto beside = RT_GRADED(scene.closest_hit)(Ray{Vec3(0.7f, 0, 0), Vec3(0, 1, 0)}, Interval::positive());
  ASSERT_TRUE(beside);
  EXPECT_EQ(beside->primitive, 2);
  EXPECT_EQ(scene.emitter_index(*beside), 1);
  EXPECT_TRUE(std::holds_alternative<RectangleEmitter>(scene.emitters()[1].geometry));
  // Both of the rectangle's triangles are the one emitter.
  const auto other_half = RT_GRADED(scene.closest_hit)(Ray{Vec3(-0.7f, 0, 0.5f), Vec3(0, 1, 0)}, Interval::positive());
  ASSERT_TRUE(other_half);
  EXPECT_NE(other_half->triangle, beside->triangle);
  EXPECT_EQ(scene.emitter_index(*other_half), 1);
  const auto down = RT_GRADED(scene.closest_hit)(Ray{Vec3(0, 0, 0), Vec3(0, -1, 0)}, Interval::positive());
  ASSERT_TRUE(down);
  EXPECT_EQ(down->primitive, 0);  // the shape's index in the file, whatever its kind
  EXPECT_EQ(scene.emitter_index(*down), -1);
  EXPECT_TRUE(RT_GRADED(scene.occluded)(Ray{Vec3(0.1f, 0, 0), Vec3(0, 1, 0)}, Interval{0.0f, 2.0f}));
  EXPECT_FALSE(RT_GRADED(scene.occluded)(Ray{Vec3(0.1f, 0, 0), Vec3(0, 1, 0)}, Interval{0.0f, 0.9f}));
}

// Disks lie in the BVH with the other kinds (DiskKind, 04-radiometry/disk_kind.h): every tree
// must find exactly what brute force finds, also for rays aimed just inside a disk's rim, which a
// disk's box must not cut off (its extent r sqrt(1 - n_i^2) per axis, zero along an axis normal).
TEST(LightingScene, DisksInTheBvhAgreeWithBruteForce) {
  auto set = std::make_shared<LightingPrimitives>();
  Rng rng(77, 0, 0);
  auto unit = [&] { return glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f); };
  auto point = [&] { return Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 8.0f - 4.0f; };
  const Vec3 axes[] = {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  std::vector<Disk> disks;
  for (int i = 0; i < 60; ++i) disks.push_back(Disk{point(), i < 30 ? axes[i % 3] : unit(), 0.2f + rng.uniform()});
  for (const Disk& d : disks) set->store_of<DiskKind>().push_back({d, 0, 0});
  for (int i = 0; i < 10; ++i) set->store_of<SphereKind>().push_back({Sphere{point(), 0.3f}, 0, 0});
  set->store_of<TriangleKind>().add_mesh(make_uv_sphere(8, 16, 0.1f, 3), 0, 0);

  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    const Disk& d = disks[size_t(i) % disks.size()];
    const Frame frame = Frame::from_normal(d.normal);
    const float phi = 2.0f * kPi * rng.uniform();
    const float radius = d.radius * (i % 2 ? 0.9999f : rng.uniform());  // every other ray at the rim
    const Vec3 target = d.center + radius * (std::cos(phi) * frame.s + std::sin(phi) * frame.t);
    const Vec3 origin = target + 10.0f * unit();
    rays.push_back(Ray{origin, glm::normalize(target - origin)});
  }
  const NaiveAggregate naive(set);
  for (const bool wide : {false, true}) {
    const BvhAggregate bvh(set, BvhBuildOptions{.wide = wide});
    int disk_hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const auto a = RT_GRADED(naive.closest_hit)(rays[i], Interval::positive());
      const auto b = RT_GRADED(bvh.closest_hit)(rays[i], Interval::positive());
      ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i << (wide ? ", 4-wide" : "");
      if (!a) continue;
      EXPECT_EQ(a->t, b->t) << "ray " << i;
      EXPECT_EQ(a->kind, b->kind) << "ray " << i;
      EXPECT_EQ(a->index, b->index) << "ray " << i;
      disk_hits += a->kind == LightingPrimitives::index_of<DiskKind>() ? 1 : 0;
      EXPECT_EQ(RT_GRADED(bvh.occluded)(rays[i], Interval::positive()), true) << "ray " << i;
    }
    EXPECT_GT(disk_hits, 2000) << "the rays are aimed at disks and must mostly hit one";
  }
}

// A disk's box holds its whole rim, also when the disk is tilted from an axis by so little that
// n_i rounds to 1 (where r sqrt(1 - n_i^2) would cancel to a flat box), and the box is tight.
TEST(LightingScene, DiskBoxesHoldTheirRims) {
  const Vec3 normals[] = {Vec3(0, 1, 0), glm::normalize(Vec3(1e-4f, 1, 0)), glm::normalize(Vec3(0, -3e-4f, 1)),
                          glm::normalize(Vec3(1, 1, 1)), glm::normalize(Vec3(0.2f, -0.9f, 0.1f))};
  for (const Vec3& n : normals) {
    const Disk disk{Vec3(3, -2, 5), n, 1.5f};
    const Aabb box = DiskKind::bounds(disk);
    // The rim in double: c + r (cos(phi) s + sin(phi) t), for an orthonormal s, t across n.
    const glm::dvec3 dn = glm::normalize(glm::dvec3(n));
    const glm::dvec3 s = glm::normalize(glm::cross(dn, std::abs(dn.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 t = glm::cross(dn, s);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (int k = 0; k < 3600; ++k) {
      const double phi = 2.0 * 3.14159265358979323846 * k / 3600.0;
      const glm::dvec3 p = glm::dvec3(disk.center) + double(disk.radius) * (std::cos(phi) * s + std::sin(phi) * t);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
      for (int axis = 0; axis < 3; ++axis) {
        ASSERT_LE(double(box.lo[axis]), p[axis]) << "axis " << axis << ", normal " << n.x << " " << n.y << " " << n.z;
        ASSERT_GE(double(box.hi[axis]), p[axis]) << "axis " << axis << ", normal " << n.x << " " << n.y << " " << n.z;
      }
    }
    for (int axis = 0; axis < 3; ++axis) {  // and no looser than the rim's own extent needs
      EXPECT_NEAR(double(box.hi[axis] - box.lo[axis]), hi[axis] - lo[axis], 1e-3 * disk.radius) << "axis " << axis;
    }
  }
}

}  // namespace
}  // namespace rt
