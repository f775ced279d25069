#include "01-ray-casting/render.h"
#include "02-whitted/whitted.h"

#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::source_path;
using testing::subject;

Material mirror(Color reflectance) {
  Material m;
  m.type = MaterialType::mirror;
  m.reflectance = reflectance;
  return m;
}
Material glass(float ior) {
  Material m;
  m.type = MaterialType::dielectric;
  m.ior = ior;
  return m;
}

SceneDescription scene_of(std::vector<Material> materials, std::vector<Shape> shapes, Color background,
                          std::vector<PointLight> lights = {}) {
  SceneDescription d;
  d.materials = std::move(materials);
  d.shapes = std::move(shapes);
  d.background = background;
  d.lights = std::move(lights);
  return d;
}

WhittedOptions depth(int max_depth, FresnelModel fresnel = FresnelModel::exact, float min_weight = 1e-4f) {
  WhittedOptions o;
  o.max_depth = max_depth;
  o.fresnel = fresnel;
  o.min_weight = min_weight;
  return o;
}

TEST(Whitted, MirrorShowsWhatItFacesTimesItsReflectance) {
  // A mirror square at z = 2 facing the camera: the reflected ray leaves to the background.
  const Color background(0.2f, 0.4f, 0.8f), reflectance(0.9f, 0.5f, 0.25f);
  const WhittedScene scene(scene_of({mirror(reflectance)},
                                    {Shape{"mirror", Quad{{Vec3(-1, -1, 2), Vec3(-1, 1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2)}}, 0}},
                                    background));
  const Ray ray{Vec3(0.1f, 0.2f, 0), glm::normalize(Vec3(0.1f, 0, 1))};
  const Color seen = subject([&] { return whitted_radiance(scene, ray, depth(5)); });
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], reflectance[c] * background[c], 1e-6f);
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, ray, depth(0)); }), Color(0.0f)) << "no bounce allowed: black";
}

// Two 2 x 2 mirrors of reflectance 0.5 facing each other at z = 0 and z = 2, white all round.
SceneDescription facing_mirrors() {
  return scene_of({mirror(Color(0.5f))},
                  {Shape{"near", Quad{{Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}}, 0},
                   Shape{"far", Quad{{Vec3(-1, -1, 2), Vec3(-1, 1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2)}}, 0}},
                  Color(1.0f));
}

TEST(Whitted, TwoFacingMirrorsStopAtTheDepthLimit) {
  // Parallel mirrors at z = 0 and z = 2; a ray bouncing straight between them never escapes, and
  // every depth limit gives black. A slanted ray escapes after the bounces it needs, each
  // weighted by the reflectance 0.5.
  const WhittedScene scene(facing_mirrors());
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, Ray{Vec3(0, 0, 1), Vec3(0, 0, 1)}, depth(50)); }), Color(0.0f));
  // From (0.5, 0, 1) at 45 degrees in x: hits z = 2 at x = 1.5 > 1: escapes at once.
  // Aimed more steeply, slope 0.3 per unit z: x = 0.5, 0.8, 1.4 -> hits at x = 0.8, then escapes.
  const Ray steep{Vec3(0.5f, 0, 1), glm::normalize(Vec3(0.3f, 0, 1))};
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, steep, depth(5)); }).r, 0.5f, 1e-6f);
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, steep, depth(0)); }), Color(0.0f));
}

TEST(Whitted, BranchPruningWeighsEachBranchByTheReflectancesBehindIt) {
  // From x = -0.9 with slope 0.3 per unit z the ray meets the mirrors at x = -0.6, 0, 0.6 and
  // escapes: 0.5^3 of the background. Its third reflection carries weight 0.125, so a threshold
  // above that prunes it (black), and one at or below it does not.
  const WhittedScene scene(facing_mirrors());
  const Ray ray{Vec3(-0.9f, 0, 1), glm::normalize(Vec3(0.3f, 0, 1))};
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(10, FresnelModel::exact, 0.1f)); }).r, 0.125f, 1e-6f);
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(10, FresnelModel::exact, 0.125f)); }).r, 0.125f, 1e-6f);
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, ray, depth(10, FresnelModel::exact, 0.2f)); }), Color(0.0f));
}

// A glass ball in a uniform environment neither absorbs nor emits, so with R + T = 1 at every
// interface it returns exactly the environment's radiance (a furnace test for the recursion).
// Rays stay within |x| < 0.85 of the axis, where the light lost to the depth limit is below 1e-5;
// branch pruning is off (min_weight 0), so nothing else is lost.
TEST(Whitted, GlassBallInAUniformEnvironmentDisappears) {
  const Color environment(0.7f, 0.5f, 0.3f);
  const WhittedScene scene(scene_of({glass(1.5f)}, {Shape{"ball", Sphere{Vec3(0), 1.0f}, 0}}, environment));
  for (const FresnelModel model : {FresnelModel::exact, FresnelModel::schlick})
    for (int i = -17; i <= 17; ++i) {
      const Ray ray{Vec3(0.05f * float(i), 0.01f * float(i), -5), Vec3(0, 0, 1)};
      const Color seen = subject([&] { return whitted_radiance(scene, ray, depth(16, model, 0.0f)); });
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], environment[c], 1e-5f) << "ray " << i;
    }
}

// A glass slab 0.2 thick across z = 0, white beyond it, a black wall behind the camera (z < 0).
SceneDescription glass_slab() {
  Material black;
  black.albedo = Color(0.0f);
  const float h = 0.1f;
  return scene_of({glass(1.5f), black},
                  {Shape{"front", Quad{{Vec3(-1, -1, -h), Vec3(-1, 1, -h), Vec3(1, 1, -h), Vec3(1, -1, -h)}}, 0},
                   Shape{"back", Quad{{Vec3(-1, -1, h), Vec3(1, -1, h), Vec3(1, 1, h), Vec3(-1, 1, h)}}, 0},
                   Shape{"wall behind", Quad{{Vec3(-5, -5, -2), Vec3(5, -5, -2), Vec3(5, 5, -2), Vec3(-5, 5, -2)}}, 1}},
                  Color(1.0f));
}

TEST(Whitted, GlassSlabPassesWhatFresnelLetsThrough) {
  // A glass slab seen face-on, white beyond it, a black wall behind the camera. Each face
  // reflects R = 0.04 at normal incidence; light bouncing inside the slab forms a geometric
  // series, so the slab passes (1 - R)^2 (1 + R^2 + R^4 + ...) = (1 - R)^2 / (1 - R^2) = 0.923077.
  const WhittedScene scene(glass_slab());
  const Color seen = subject([&] { return whitted_radiance(scene, Ray{Vec3(0.2f, 0.1f, -1), Vec3(0, 0, 1)}, depth(30)); });
  const float r = 0.04f;
  EXPECT_NEAR(seen.r, (1 - r) * (1 - r) / (1 - r * r), 1e-5f);
}

TEST(Whitted, TheDepthLimitCountsRefractedRaysToo) {
  // The slab above, face-on: through it takes two refractions, so a limit of one bounce lets
  // nothing through (the front's reflection meets the black wall), and a limit of two lets through
  // (1 - R)^2 exactly, without the slab's inner reflections, which need four.
  const WhittedScene scene(glass_slab());
  const Ray ray{Vec3(0.2f, 0.1f, -1), Vec3(0, 0, 1)};
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, ray, depth(1)); }), Color(0.0f));
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(2)); }).r, 0.96f * 0.96f, 1e-5f);
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(3)); }).r, 0.96f * 0.96f, 1e-5f);
}

// One glass surface, an 18 x 18 square in the plane y = 0, white all round: a ray refracted into it
// meets nothing more.
SceneDescription glass_surface() {
  return scene_of({glass(1.5f)}, {Shape{"glass", Quad{{Vec3(-9, 0, -9), Vec3(-9, 0, 9), Vec3(9, 0, 9), Vec3(9, 0, -9)}}, 0}},
                  Color(1.0f));
}

TEST(Whitted, BranchPruningWeighsTheRefractedBranchByTheLightItPasses) {
  // The glass surface seen at 87 degrees from its normal: it reflects R > 1/2 and passes 1 - R into
  // the glass. Unpruned, R + (1 - R) = 1; with a
  // threshold of 1/2 the refracted branch, of weight 1 - R, is cut off and only R is left.
  const WhittedScene scene(glass_surface());
  const float cos_i = 0.05f;
  const Ray ray{Vec3(-15, 0.5f, 0), Vec3(std::sqrt(1.0f - cos_i * cos_i), -cos_i, 0)};  // meets it at x = -5
  const float r = subject([&] { return fresnel_dielectric(cos_i, 1.0f, 1.5f); });
  ASSERT_GT(r, 0.5f);
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(5, FresnelModel::exact, 0.0f)); }).r, 1.0f, 1e-5f);
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(5, FresnelModel::exact, 0.5f)); }).r, r, 1e-5f);
}

TEST(Whitted, BranchPruningWeighsTheReflectedBranchByTheLightItReflects) {
  // The same surface seen face-on: it reflects R = 0.04 and passes 0.96. With a threshold of 0.1
  // the reflected branch, of weight R, is cut off and only 1 - R is left.
  const WhittedScene scene(glass_surface());
  const Ray ray{Vec3(0.5f, 2, 0.25f), Vec3(0, -1, 0)};
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(5, FresnelModel::exact, 0.0f)); }).r, 1.0f, 1e-5f);
  EXPECT_NEAR(subject([&] { return whitted_radiance(scene, ray, depth(5, FresnelModel::exact, 0.1f)); }).r, 0.96f, 1e-5f);
}

TEST(Whitted, BranchPruningBoundsTheRayTreeBetweenGlassAndMirrors) {
  // A glass slab between two perfect mirrors: every ray splits at each glass face and nothing
  // is absorbed, so without pruning the tree would hold 2^200 rays. With it, at most 1 / min_weight
  // branches per depth are followed; what is cut off is dark (no light reaches inside), so the
  // answer is 0 either way, and it must come back at all.
  Material black;
  black.albedo = Color(0.0f);
  auto square = [](float z, bool facing_minus_z) {
    return facing_minus_z ? Quad{{Vec3(-9, -9, z), Vec3(-9, 9, z), Vec3(9, 9, z), Vec3(9, -9, z)}}
                          : Quad{{Vec3(-9, -9, z), Vec3(9, -9, z), Vec3(9, 9, z), Vec3(-9, 9, z)}};
  };
  const WhittedScene scene(scene_of({mirror(Color(1.0f)), glass(1.5f)},
                                    {Shape{"mirror", square(0, false), 0}, Shape{"mirror", square(2, true), 0},
                                     Shape{"glass", square(0.9f, true), 1}, Shape{"glass", square(1.1f, false), 1}},
                                    Color(1.0f)));
  const Color seen = subject([&] { return whitted_radiance(scene, Ray{Vec3(0.1f, 0.2f, 0.5f), glm::normalize(Vec3(0.01f, 0.02f, 1))}, depth(200)); });
  EXPECT_TRUE(is_finite(seen));
  EXPECT_LT(seen.r, 1e-3f);
}

TEST(Whitted, TotalInternalReflectionTrapsLightInsideGlass) {
  // From inside a glass ball, a ray meeting the surface at sin(theta) = 0.9 > 1 / 1.5 reflects
  // completely, and keeps doing so at the same angle: it never gets out.
  const WhittedScene scene(scene_of({glass(1.5f)}, {Shape{"ball", Sphere{Vec3(0), 1.0f}, 0}}, Color(1.0f)));
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, Ray{Vec3(0, 0.9f, 0), Vec3(1, 0, 0)}, depth(40)); }), Color(0.0f));
  // At sin(theta) = 0.3 most of it leaves: 1 - F(leaving, 0.3) plus what comes back around.
  const Color escapes = subject([&] { return whitted_radiance(scene, Ray{Vec3(0, 0.3f, 0), Vec3(1, 0, 0)}, depth(40)); });
  EXPECT_GT(escapes.r, 0.99f);
}

TEST(Whitted, DiffuseSurfaceFollowsInverseSquareAndCosineLaws) {
  // Lambertian floor (albedo 0.6), light of 10 W/sr at height 2. At horizontal distance 1.5:
  // r = 2.5, cos = 0.8, E = 10 * 0.8 / 6.25 = 1.28, L = 0.6 / pi * 1.28.
  Material floor;
  floor.albedo = Color(0.6f);
  const WhittedScene scene(scene_of({floor}, {Shape{"floor", Plane{Vec3(0), Vec3(0, 1, 0)}, 0}}, Color(0.0f),
                                    {PointLight{Vec3(0, 2, 0), Color(10.0f)}}));
  const Vec3 target(1.5f, 0, 0), eye(1.5f, 1, -1);
  const Color seen = subject([&] { return whitted_radiance(scene, Ray{eye, glm::normalize(target - eye)}, depth(5)); });
  EXPECT_NEAR(seen.r, 0.6f / kPi * 1.28f, 1e-5f);
}

TEST(Whitted, ShadowsAndOneSidedEmission) {
  Material floor, lamp;
  lamp.albedo = Color(0.0f);
  lamp.emission = Color(3.0f);
  const WhittedScene scene(scene_of({floor, lamp},
                                    {Shape{"floor", Plane{Vec3(0), Vec3(0, 1, 0)}, 0},
                                     Shape{"blocker", Sphere{Vec3(0, 1, 0), 0.5f}, 0},
                                     Shape{"lamp", Quad{{Vec3(3, 1, 0), Vec3(3, 2, 0), Vec3(4, 2, 0), Vec3(4, 1, 0)}}, 1}},
                                    Color(0.0f), {PointLight{Vec3(0, 2, 0), Color(10.0f)}}));
  const Vec3 eye(0.3f, 3, -3);
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, Ray{eye, glm::normalize(Vec3(0, 0, 0) - eye)}, depth(5)); }), Color(0.0f))
      << "the point under the ball is in its shadow";
  // The lamp's outward normal is (v1 - v0) x (v2 - v0) = (0,1,0) x (1,1,0) = -z: it faces the camera.
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, Ray{Vec3(3.5f, 1.5f, -5), Vec3(0, 0, 1)}, depth(5)); }), Color(3.0f));
  EXPECT_EQ(subject([&] { return whitted_radiance(scene, Ray{Vec3(3.5f, 1.5f, 5), Vec3(0, 0, -1)}, depth(5)); }), Color(0.0f))
      << "emission leaves the front face only";
}

// An interpolated shading normal may lean towards a light that the surface itself does not face.
// The light counts only when it is strictly in front of the geometric surface: one exactly in the
// surface's plane gives nothing (its light arrives at grazing incidence, cos = 0), one a hair above
// it gives some.
TEST(Whitted, ALightInTheSurfacesPlaneGivesNothingWhereverTheShadingNormalLeans) {
  Material floor;
  Hit hit;
  hit.point = Vec3(0.0f);
  hit.normal = Vec3(0, 1, 0);
  hit.shading_normal = glm::normalize(Vec3(1, 1, 0));  // leaning towards +x, where the lights are
  hit.material = 0;
  const auto lit_by = [&](Vec3 light) {
    const WhittedScene scene(scene_of({floor}, {Shape{"floor", Plane{Vec3(0), Vec3(0, 1, 0)}, 0}}, Color(0.0f),
                                      {PointLight{light, Color(10.0f)}}));
    return subject([&] { return shade_direct(scene, hit, Vec3(0, 1, 0), OffsetPolicy{}); });
  };
  EXPECT_EQ(lit_by(Vec3(2, 0, 0)), Color(0.0f)) << "a light in the plane";
  EXPECT_EQ(lit_by(Vec3(2, -1e-3f, 0)), Color(0.0f)) << "a light below the plane";
  EXPECT_GT(lit_by(Vec3(2, 1e-3f, 0)).r, 0.0f) << "a light just above the plane";
}

TEST(Whitted, CheckerAlternatesAndIsStableOnItsPlane) {
  Material checks;
  checks.albedo = Color(1, 0, 0);
  checks.checker = Checker{Color(0, 0, 1), 2.0f};
  EXPECT_EQ(checks.albedo_at(Vec3(0.5f, 0, 0.5f)), Color(1, 0, 0));
  EXPECT_EQ(checks.albedo_at(Vec3(2.5f, 0, 0.5f)), Color(0, 0, 1));
  EXPECT_EQ(checks.albedo_at(Vec3(2.5f, 0, 2.5f)), Color(1, 0, 0));
  EXPECT_EQ(checks.albedo_at(Vec3(-2.5f, 0, 0.5f)), Color(0, 0, 1));
  // Rounding either side of the plane y = 0 must not change the colour.
  for (const float y : {-1e-6f, 0.0f, 1e-6f}) {
    EXPECT_EQ(checks.albedo_at(Vec3(2.5f, y, 0.5f)), Color(0, 0, 1));
  }
}

class WhittedScenes : public ::testing::Test {
 protected:
  static Image render(const std::string& file, int size, int threads) {
    const SceneDescription d = load_scene(source_path(file));
    RenderSettings s = d.render;
    s.width = size;
    s.height = size;
    s.spp = 2;
    const WhittedScene scene(d);
    WhittedOptions options;
    options.max_depth = s.max_depth;
    return subject([&] {
      return render_image(Camera(d.camera, s.width, s.height), s, threads,
                          [&](const Ray& ray, Rng&) { return whitted_radiance(scene, ray, options); });
    });
  }
};

TEST_F(WhittedScenes, SameImageForAnyThreadCount) {
  EXPECT_TRUE(render("assets/scenes/whitted.json", 48, 1) == render("assets/scenes/whitted.json", 48, 2));
}

TEST_F(WhittedScenes, CornellBoxHasRedOnTheLeftAndGreenOnTheRight) {
  const Image image = render("assets/scenes/cornell-box-point-light.json", 32, 2);
  for (const Color& c : image.pixels()) ASSERT_TRUE(is_finite(c));
  const Color left = image.at(1, 16), right = image.at(30, 16);
  EXPECT_GT(left.r, 3.0f * left.g) << "red wall";
  EXPECT_GT(right.g, 2.0f * right.r) << "green wall";
  float brightest_at_top = 0.0f;
  for (int y = 0; y < 8; ++y) brightest_at_top = std::max(brightest_at_top, image.at(16, y).r);
  EXPECT_GT(brightest_at_top, 10.0f) << "the emitter is seen directly near the top";
  EXPECT_EQ(WhittedScene(load_scene(source_path("assets/scenes/cornell-box-point-light.json"))).triangle_count(), 32u);
}

}  // namespace
}  // namespace rt
