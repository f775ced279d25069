// Stage 4: image textures. The lookup's arithmetic on textures small enough to check by hand (wrap
// modes at and beyond the edges, bilinear weights that are exact binary fractions), the texture
// coordinates each shape reports, and that a texture reaches the BRDF the right way up.
#include "01-ray-casting/render.h"
#include "04-radiometry/direct_lighting.h"
#include "04-radiometry/texture.h"
#include "common/spherical.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <memory>

namespace rt {
namespace {

const Color kTopLeft(1.0f, 0.0f, 0.0f), kTopRight(0.0f, 1.0f, 0.0f), kBottomLeft(0.0f, 0.0f, 1.0f),
    kBottomRight(1.0f, 1.0f, 1.0f);

// 2 x 2 texels, row 0 (the top) first.
ImageTexture two_by_two(TextureWrap wrap, TextureFilter filter) {
  ImageTexture t;
  auto texels = std::make_shared<Image>(2, 2);
  texels->at(0, 0) = kTopLeft;
  texels->at(1, 0) = kTopRight;
  texels->at(0, 1) = kBottomLeft;
  texels->at(1, 1) = kBottomRight;
  t.texels = texels;
  t.wrap = wrap;
  t.filter = filter;
  return t;
}

TEST(WrapTexel, RepeatIsModuloWithoutNegativeResults) {
  EXPECT_EQ(RT_GRADED(wrap_texel)(0, 4, TextureWrap::repeat), 0);
  EXPECT_EQ(RT_GRADED(wrap_texel)(3, 4, TextureWrap::repeat), 3);
  EXPECT_EQ(RT_GRADED(wrap_texel)(4, 4, TextureWrap::repeat), 0);
  EXPECT_EQ(RT_GRADED(wrap_texel)(9, 4, TextureWrap::repeat), 1);
  EXPECT_EQ(RT_GRADED(wrap_texel)(-1, 4, TextureWrap::repeat), 3);
  EXPECT_EQ(RT_GRADED(wrap_texel)(-4, 4, TextureWrap::repeat), 0);
  EXPECT_EQ(RT_GRADED(wrap_texel)(-5, 4, TextureWrap::repeat), 3);
  EXPECT_EQ(RT_GRADED(wrap_texel)(-1, 1, TextureWrap::repeat), 0);
}

TEST(WrapTexel, ClampStopsAtBothEdges) {
  EXPECT_EQ(RT_GRADED(wrap_texel)(-1, 4, TextureWrap::clamp), 0);
  EXPECT_EQ(RT_GRADED(wrap_texel)(0, 4, TextureWrap::clamp), 0);
  EXPECT_EQ(RT_GRADED(wrap_texel)(3, 4, TextureWrap::clamp), 3);
  EXPECT_EQ(RT_GRADED(wrap_texel)(4, 4, TextureWrap::clamp), 3);
  EXPECT_EQ(RT_GRADED(wrap_texel)(1000, 4, TextureWrap::clamp), 3);
}

TEST(TextureLookup, NearestReturnsTheTexelThatCoversTheCoordinates) {
  const ImageTexture t = two_by_two(TextureWrap::clamp, TextureFilter::nearest);
  // v runs up: the top row holds v in (0.5, 1].
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.1f, 0.9f)), kTopLeft);
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.9f, 0.9f)), kTopRight);
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.1f, 0.1f)), kBottomLeft);
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.9f, 0.1f)), kBottomRight);
  // Texel (i, j) covers [i, i + 1) x [j, j + 1) of (u W, (1 - v) H): the boundary u = 0.5 belongs
  // to the right-hand column, and v = 0.5 ((1 - v) H = 1) to the bottom row.
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.5f, 0.25f)), kBottomRight);
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.25f, 0.5f)), kBottomLeft);
}

TEST(TextureLookup, BilinearWeightsAreExactOnTwoByTwo) {
  const ImageTexture t = two_by_two(TextureWrap::clamp, TextureFilter::bilinear);
  // At a texel's centre, that texel alone.
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.25f, 0.75f)), kTopLeft);
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.75f, 0.25f)), kBottomRight);
  // Midway between all four centres: each weighs 1/4.
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.5f, 0.5f)),
            0.25f * (kTopLeft + kTopRight + kBottomLeft + kBottomRight));
  // A quarter of the way from the top-left centre to the top-right one: weights 3/4 and 1/4.
  EXPECT_EQ(RT_GRADED(texture_lookup)(t, Vec2(0.375f, 0.75f)), 0.75f * kTopLeft + 0.25f * kTopRight);
  // And a quarter of the way down too: (3/4)(3/4), (1/4)(3/4), (3/4)(1/4), (1/4)(1/4).
  const Color expected = 0.5625f * kTopLeft + 0.1875f * kTopRight + 0.1875f * kBottomLeft + 0.0625f * kBottomRight;
  const Color got = RT_GRADED(texture_lookup)(t, Vec2(0.375f, 0.625f));
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(got[c], expected[c]) << "channel " << c;
}

TEST(TextureLookup, EdgesFollowTheWrapMode) {
  // At the corner (0, 0), clamp sees only the bottom-left texel; repeat blends the four texels that
  // meet there once the image is tiled.
  EXPECT_EQ(RT_GRADED(texture_lookup)(two_by_two(TextureWrap::clamp, TextureFilter::bilinear), Vec2(0.0f)),
            kBottomLeft);
  EXPECT_EQ(RT_GRADED(texture_lookup)(two_by_two(TextureWrap::repeat, TextureFilter::bilinear), Vec2(0.0f)),
            0.25f * (kTopLeft + kTopRight + kBottomLeft + kBottomRight));
  // Repeat: whole periods away, the same value; clamp: beyond the edge, the edge.
  const ImageTexture repeat = two_by_two(TextureWrap::repeat, TextureFilter::nearest);
  EXPECT_EQ(RT_GRADED(texture_lookup)(repeat, Vec2(3.1f, -1.1f)), RT_GRADED(texture_lookup)(repeat, Vec2(0.1f, 0.9f)));
  EXPECT_EQ(RT_GRADED(texture_lookup)(repeat, Vec2(3.1f, -1.1f)), kTopLeft);
  const ImageTexture clamp = two_by_two(TextureWrap::clamp, TextureFilter::nearest);
  EXPECT_EQ(RT_GRADED(texture_lookup)(clamp, Vec2(-7.0f, 5.0f)), kTopLeft);
  EXPECT_EQ(RT_GRADED(texture_lookup)(clamp, Vec2(1.0f, 0.0f)), kBottomRight);
}

TEST(TextureLookup, HugeAndNonFiniteCoordinatesStayInside) {
  for (const TextureWrap wrap : {TextureWrap::repeat, TextureWrap::clamp})
    for (const TextureFilter filter : {TextureFilter::nearest, TextureFilter::bilinear}) {
      const ImageTexture t = two_by_two(wrap, filter);
      for (const Vec2 uv : {Vec2(1e18f, -1e18f), Vec2(-3e38f, 3e38f), Vec2(kInfinity, 0.5f), Vec2(std::nanf(""), 0.5f)}) {
        const Color c = RT_GRADED(texture_lookup)(t, uv);
        EXPECT_TRUE(is_finite(c) && min_component(c) >= 0.0f && max_component(c) <= 1.0f);
      }
    }
}

TEST(TextureLookup, OneColourTextureReturnsItsColourBitForBit) {
  ImageTexture t;
  t.texels = std::make_shared<Image>(3, 5, Color(0.2158605f, 0.5f, 0.0033465f));
  for (const TextureFilter filter : {TextureFilter::nearest, TextureFilter::bilinear})
    for (const TextureWrap wrap : {TextureWrap::repeat, TextureWrap::clamp}) {
      t.filter = filter;
      t.wrap = wrap;
      for (const Vec2 uv : {Vec2(0.0f), Vec2(0.123f, 0.877f), Vec2(0.99f, 0.51f), Vec2(-2.3f, 7.7f)})
        EXPECT_EQ(RT_GRADED(texture_lookup)(t, uv), t.texels->at(0, 0));
    }
}

// Texture coordinates as the shapes report them (docs/scene-format.md).
Hit first_hit(const LightingScene& scene, Vec3 from, Vec3 to) {
  const std::optional<Hit> hit =
      RT_GRADED(scene.closest_hit)(Ray{from, glm::normalize(to - from)}, Interval::positive());
  EXPECT_TRUE(hit.has_value());
  return hit.value_or(Hit{});
}

SceneDescription one_shape(Geometry geometry) {
  SceneDescription d;
  d.source = "test";
  d.materials.push_back(Material{});
  d.shapes.push_back(Shape{"", std::move(geometry), 0});
  return d;
}

TEST(TextureCoordinates, QuadCornersAreTheUnitSquareCounterClockwise) {
  const LightingScene scene(one_shape(Quad{{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)}}));
  const Vec3 eye(1.0f, 0.5f, 3.0f);
  const Hit near_v3 = first_hit(scene, eye, Vec3(0.02f, 0.99f, 0.0f));  // corner v3: (0, 1)
  EXPECT_NEAR(near_v3.uv.x, 0.01f, 1e-5f);
  EXPECT_NEAR(near_v3.uv.y, 0.99f, 1e-5f);
  const Hit inner = first_hit(scene, eye, Vec3(1.5f, 0.25f, 0.0f));
  EXPECT_NEAR(inner.uv.x, 0.75f, 1e-5f);
  EXPECT_NEAR(inner.uv.y, 0.25f, 1e-5f);
}

TEST(TextureCoordinates, TriangleInterpolatesItsGivenCoordinates) {
  Triangle triangle{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}};
  triangle.uvs = {Vec2(0.5f, 0.5f), Vec2(1.5f, 0.5f), Vec2(0.5f, 2.5f)};
  const LightingScene scene(one_shape(triangle));
  const Hit hit = first_hit(scene, Vec3(0.25f, 0.25f, 2.0f), Vec3(0.25f, 0.25f, 0.0f));
  // Barycentrics (1/2, 1/4, 1/4): 0.5 (0.5, 0.5) + 0.25 (1.5, 0.5) + 0.25 (0.5, 2.5).
  EXPECT_NEAR(hit.uv.x, 0.75f, 1e-6f);
  EXPECT_NEAR(hit.uv.y, 1.0f, 1e-6f);
}

TEST(TextureCoordinates, SphereUsesLatitudeAndLongitude) {
  const LightingScene scene(one_shape(Sphere{Vec3(0.0f), 1.0f}));
  // From +x the ray meets the sphere at phi = 0, on the equator: (0, 1/2).
  const Hit x = first_hit(scene, Vec3(5, 0, 0), Vec3(0.0f));
  EXPECT_NEAR(x.uv.x, 0.0f, 1e-6f);
  EXPECT_NEAR(x.uv.y, 0.5f, 1e-6f);
  // +z is phi = pi / 2: u = 1/4; -x is u = 1/2; -z is u = 3/4.
  EXPECT_NEAR(first_hit(scene, Vec3(0, 0, 5), Vec3(0.0f)).uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(first_hit(scene, Vec3(-5, 0, 0), Vec3(0.0f)).uv.x, 0.5f, 1e-6f);
  EXPECT_NEAR(first_hit(scene, Vec3(0, 0, -5), Vec3(0.0f)).uv.x, 0.75f, 1e-6f);
  // The north pole (+y) is v = 1, the south pole v = 0; 45 degrees up is v = 3/4.
  EXPECT_NEAR(first_hit(scene, Vec3(0, 5, 0), Vec3(0.0f)).uv.y, 1.0f, 1e-6f);
  EXPECT_NEAR(first_hit(scene, Vec3(0, -5, 0), Vec3(0.0f)).uv.y, 0.0f, 1e-6f);
  EXPECT_NEAR(first_hit(scene, Vec3(5, 5, 0), Vec3(0.0f)).uv.y, 0.75f, 1e-6f);
}

TEST(TextureCoordinates, LatLongMapRoundTrips) {
  for (const Vec2 uv : {Vec2(0.1f, 0.2f), Vec2(0.5f, 0.5f), Vec2(0.9f, 0.95f), Vec2(0.3f, 0.01f)}) {
    const Vec2 back = latlong_uv(latlong_direction(uv));
    EXPECT_NEAR(back.x, uv.x, 1e-5f);
    EXPECT_NEAR(back.y, uv.y, 1e-5f);
  }
  // Just below phi = 2 pi, u must stay below 1 (a texel index of W would be out of the image).
  EXPECT_LT(latlong_uv(Vec3(1.0f, 0.0f, -1e-9f)).x, 1.0f);
}

TEST(TextureCoordinates, DiskFillsTheUnitSquareAndPlaneCountsSceneUnits) {
  const LightingScene disk(one_shape(Disk{Vec3(0.0f), Vec3(0, 1, 0), 2.0f}));
  const Hit centre = first_hit(disk, Vec3(0, 3, 0), Vec3(0.0f));
  EXPECT_NEAR(centre.uv.x, 0.5f, 1e-6f);
  EXPECT_NEAR(centre.uv.y, 0.5f, 1e-6f);
  const Hit rim = first_hit(disk, Vec3(1.99f, 3.0f, 0.0f), Vec3(1.99f, 0.0f, 0.0f));
  EXPECT_NEAR(glm::length(rim.uv - Vec2(0.5f)), 0.4975f, 1e-5f) << "radius 2 maps to 1/2";

  const LightingScene plane(one_shape(Plane{Vec3(0.0f), Vec3(0, 1, 0)}));
  const Hit a = first_hit(plane, Vec3(0, 3, 0), Vec3(0.0f));
  const Hit b = first_hit(plane, Vec3(3, 4, 4), Vec3(3, 0, 4));
  EXPECT_NEAR(glm::length(a.uv), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(b.uv - a.uv), 5.0f, 1e-5f) << "one unit of u or v per scene unit";
}

// A texture reaches the BRDF: the Lambertian albedo at a hit is the texel there (-1 where the ray
// finds nothing, which no texel is).
Color albedo_seen(const LightingScene& scene, Vec3 from, Vec3 to) {
  return testing::subject([&] {
    const std::optional<Hit> hit = scene.closest_hit(Ray{from, glm::normalize(to - from)}, Interval::positive());
    if (!hit) return Color(-1.0f);
    const ShadingPoint at = make_shading_point(scene, *hit, glm::normalize(from - to));
    return at.bsdf.eval(at.wo, Vec3(0, 0, 1)) * kPi;  // f = rho / pi
  });
}

TEST(TexturedMaterial, MarkedCornerLandsTopLeftOnAQuad) {
  SceneDescription d = one_shape(Quad{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}});
  auto texture = std::make_shared<ImageTexture>(two_by_two(TextureWrap::clamp, TextureFilter::nearest));
  d.materials[0].albedo_texture = texture;
  const LightingScene scene(d);
  const Vec3 eye(0.5f, 0.5f, 3.0f);  // in front, +x to the viewer's right (the quad faces +z)
  EXPECT_EQ(albedo_seen(scene, eye, Vec3(0.1f, 0.9f, 0.0f)), kTopLeft);
  EXPECT_EQ(albedo_seen(scene, eye, Vec3(0.9f, 0.9f, 0.0f)), kTopRight);
  EXPECT_EQ(albedo_seen(scene, eye, Vec3(0.1f, 0.1f, 0.0f)), kBottomLeft);
  EXPECT_EQ(albedo_seen(scene, eye, Vec3(0.9f, 0.1f, 0.0f)), kBottomRight);
}

TEST(TexturedMaterial, SpecularTextureIsTheMicrofacetF0) {
  SceneDescription d = one_shape(Quad{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}});
  d.materials[0].type = MaterialType::microfacet;
  d.materials[0].specular = Color(1.0f);
  auto texture = std::make_shared<ImageTexture>(two_by_two(TextureWrap::clamp, TextureFilter::nearest));
  d.materials[0].specular_texture = texture;
  const LightingScene scene(d);
  const Vec3 eye(0.5f, 0.5f, 3.0f);
  // Where the texture is blue, the BRDF is the microfacet model with a blue F0.
  const Vec3 wi = glm::normalize(Vec3(0.2f, -0.1f, 1.0f));
  // The BRDF at the hit, the blue model's and the white model's, for the same pair of directions.
  const auto values = testing::subject([&]() -> std::optional<std::array<Color, 3>> {
    const std::optional<Hit> hit =
        scene.closest_hit(Ray{eye, glm::normalize(Vec3(0.1f, 0.1f, 0.0f) - eye)}, Interval::positive());
    if (!hit) return std::nullopt;
    const ShadingPoint at = make_shading_point(scene, *hit, glm::normalize(eye - hit->point));
    const Bsdf blue(MicrofacetBrdf{kBottomLeft, GgxDistribution{d.materials[0].roughness}});
    const Bsdf white(MicrofacetBrdf{Color(1.0f), GgxDistribution{d.materials[0].roughness}});
    return std::array{at.bsdf.eval(at.wo, wi), blue.eval(at.wo, wi), white.eval(at.wo, wi)};
  });
  ASSERT_TRUE(values.has_value());
  const auto& [at_hit, blue, white] = *values;
  EXPECT_EQ(at_hit, blue);
  EXPECT_NE(at_hit, white);
}

// The first promise: a one-colour texture renders exactly as the constant albedo does.
TEST(TexturedMaterial, OneColourTextureRendersLikeTheConstantBitForBit) {
  const Color albedo(0.2158605f, 0.5f, 0.4f);
  auto scene_with = [&](bool textured) {
    SceneDescription d = one_shape(Sphere{Vec3(0.0f), 1.0f});
    d.camera = CameraSpec{};
    d.camera.position = Vec3(0, 0.5f, 4);
    d.camera.look_at = Vec3(0.0f);
    d.environment = Environment{};
    d.environment->scale = Color(1.0f);
    d.materials[0].albedo = albedo;
    if (textured) {
      auto texture = std::make_shared<ImageTexture>();
      texture->texels = std::make_shared<Image>(4, 3, albedo);
      texture->mean = albedo;
      d.materials[0].albedo_texture = texture;
    }
    return d;
  };
  RenderSettings settings;
  settings.width = 24;
  settings.height = 16;
  settings.spp = 4;
  Image images[2];
  for (int textured = 0; textured < 2; ++textured) {
    const SceneDescription d = scene_with(textured == 1);
    const LightingScene scene(d);
    const Camera camera(d.camera, settings.width, settings.height);
    images[textured] = testing::subject([&] {
      return render_image(camera, settings, 1, [&](const Ray& ray, Sampler& rng) {
        return direct_radiance(scene, ray, DirectOptions{}, rng);
      });
    });
  }
  // The centre is the ball (lit, and darker than the environment's 1 around it), not the sky.
  Color centre(0.0f);
  for (int y = 6; y < 10; ++y)
    for (int x = 10; x < 14; ++x) centre += images[0].at(x, y) / 16.0f;
  EXPECT_GT(centre.g, 0.2f);
  EXPECT_LT(centre.g, 0.8f);
  EXPECT_TRUE(images[0] == images[1]);
}

}  // namespace
}  // namespace rt
