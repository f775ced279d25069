// Image files read as textures and environment maps (common/texture_image.h), and the scene keys
// that name them: texture coordinates, image textures, the environment.
#include "common/color.h"
#include "common/error.h"
#include "common/image_io.h"
#include "common/scene.h"
#include "common/texture_image.h"

#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using testing::ScratchDir;
using testing::error_message;
using testing::source_path;
using testing::write_text;

std::string bytes_of(const std::vector<char>& v) { return std::string(v.begin(), v.end()); }

TEST(SrgbDecode, ExactAtZeroOneAndTheBreakpoint) {
  EXPECT_EQ(srgb_decode(0.0f), 0.0f);
  EXPECT_EQ(srgb_decode(1.0f), 1.0f);
  // IEC 61966-2-1: the linear segment c / 12.92 up to and including 0.04045, the power curve above.
  EXPECT_EQ(srgb_decode(0.04045f), 0.04045f / 12.92f);
  EXPECT_EQ(srgb_decode(0.5f), std::pow((0.5f + 0.055f) / 1.055f, 2.4f));
  // The two pieces meet: no jump at the breakpoint.
  EXPECT_NEAR(srgb_decode(std::nextafter(0.04045f, 1.0f)), 0.04045f / 12.92f, 1e-6f);
  EXPECT_EQ(decode_texel(0, TexelEncoding::srgb), 0.0f);
  EXPECT_EQ(decode_texel(255, TexelEncoding::srgb), 1.0f);
  EXPECT_EQ(decode_texel(10, TexelEncoding::srgb), (10.0f / 255.0f) / 12.92f) << "code 10 is below the breakpoint";
  EXPECT_EQ(decode_texel(128, TexelEncoding::linear), 128.0f / 255.0f);
  // Every code round-trips through the encoder the PNG writer uses.
  for (int c = 0; c < 256; ++c)
    EXPECT_EQ(std::lround(255.0f * srgb_encode(decode_texel(std::uint8_t(c), TexelEncoding::srgb))), c);
}

TEST(TextureImage, PngDecodesToLinearOrKeepsDataCodes) {
  Image image(3, 2);
  image.at(0, 0) = Color(1.0f, 0.0f, 0.0f);  // the top-left pixel
  image.at(2, 1) = Color(decode_texel(128, TexelEncoding::srgb));
  const std::string png = bytes_of(encode_png(image));
  const Image colour = decode_texture_image(png, "t.png", TexelEncoding::srgb);
  ASSERT_EQ(colour.width(), 3);
  ASSERT_EQ(colour.height(), 2);
  EXPECT_EQ(colour.at(0, 0), Color(1.0f, 0.0f, 0.0f)) << "row 0 stays the top row";
  EXPECT_EQ(colour.at(2, 1), Color(decode_texel(128, TexelEncoding::srgb)));
  const Image data = decode_texture_image(png, "t.png", TexelEncoding::linear);
  EXPECT_EQ(data.at(2, 1), Color(128.0f / 255.0f));
}

TEST(TextureImage, PfmAndHdrAreLinear) {
  Image image(2, 2, Color(0.25f, 7.5f, 1000.0f));
  image.at(1, 0) = Color(0.0f);
  EXPECT_TRUE(decode_texture_image(bytes_of(encode_pfm(image)), "t.pfm", TexelEncoding::srgb) == image);
  // The shipped sky (tools/make_image_assets.py): 256 x 128, its sun far above 1 at theta 60
  // degrees (row 42), phi 60 degrees (column 42).
  const Image sky = read_texture_image(source_path("assets/environments/sky.hdr"), TexelEncoding::srgb);
  ASSERT_EQ(sky.width(), 256);
  ASSERT_EQ(sky.height(), 128);
  EXPECT_GT(sky.at(42, 42).r, 500.0f);
  EXPECT_LT(sky.at(42, 100).r, 1.0f) << "the ground, below the horizon";
  EXPECT_GT(sky.at(0, 0).b, sky.at(0, 0).r) << "a blue zenith";
}

TEST(TextureImage, BrokenFilesGetOneLineNamingTheFile) {
  ScratchDir scratch;
  EXPECT_NE(error_message([&] { read_texture_image(scratch / "missing.png", TexelEncoding::srgb); })
                .find("missing.png"),
            std::string::npos);
  auto message = [](const std::string& bytes, const std::string& name) {
    return error_message([&] { decode_texture_image(bytes, name, TexelEncoding::srgb); });
  };
  EXPECT_EQ(message("not an image at all", "junk.png").rfind("junk.png: not an image stb_image can read", 0), 0u);
  std::string png = bytes_of(encode_png(Image(16, 16, Color(0.5f))));
  png.resize(png.size() / 2);
  EXPECT_EQ(message(png, "cut.png").rfind("cut.png: broken image", 0), 0u) << message(png, "cut.png");
  // The header alone says 100000 x 100000: refused before a pixel is decoded.
  EXPECT_EQ(message("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n", "huge.hdr"),
            "huge.hdr: image of 100000x100000 pixels; a texture may have at most 8192x8192");
  // Found by trying: a PNG claiming 100000 x 100000 was "unknown image type" (stb_image refuses it
  // without a reason). Its IHDR chunk says the size.
  std::string huge_png = bytes_of(encode_png(Image(1, 1, Color(0.5f))));
  for (int i = 0; i < 2; ++i) {
    const std::uint32_t side = 100000;
    for (int b = 0; b < 4; ++b) huge_png[size_t(16 + 4 * i + b)] = char((side >> (24 - 8 * b)) & 0xff);
  }
  EXPECT_EQ(message(huge_png, "huge.png"), "huge.png: image of 100000x100000 pixels; a texture may have at most 8192x8192");
  Image nan(2, 1, Color(1.0f));
  nan.at(1, 0).g = std::nanf("");
  EXPECT_EQ(message(bytes_of(encode_pfm(nan)), "nan.pfm"), "nan.pfm: texel (1, 0) is not a finite, non-negative colour");
  Image negative(1, 1, Color(-1.0f));
  EXPECT_EQ(message(bytes_of(encode_pfm(negative)), "neg.pfm"), "neg.pfm: texel (0, 0) is not a finite, non-negative colour");
}

// Found by trying: a PFM texture over the size was read and decoded whole (16.8 s, 3 GB) before
// its size was checked. Its header is read first: this one claims 9000 x 9000 and has no pixels
// at all, so reading past the header would say "truncated" instead.
TEST(TextureImage, AFileOverTheSizeIsRefusedFromItsHeader) {
  ScratchDir scratch;
  write_text(scratch / "big.pfm", "PF\n9000 9000\n-1\n");
  EXPECT_EQ(error_message([&] { read_texture_image(scratch / "big.pfm", TexelEncoding::linear); }),
            (scratch / "big.pfm").string() + ": image of 9000x9000 pixels; a texture may have at most 8192x8192");
  write_text(scratch / "edge.pfm", "PF\n8192 8193\n-1\n");  // one row over 2^26 pixels
  EXPECT_NE(error_message([&] { read_texture_image(scratch / "edge.pfm", TexelEncoding::linear); })
                .find("image of 8192x8193 pixels"),
            std::string::npos);
  write_text(scratch / "fits.pfm", "PF\n8192 8192\n-1\n");  // exactly 2^26: on to the pixels, which are missing
  EXPECT_NE(error_message([&] { read_texture_image(scratch / "fits.pfm", TexelEncoding::linear); }).find("truncated"),
            std::string::npos);
}

// Scene files with textures and an environment, written next to their images.
class TexturedScene : public ::testing::Test {
 protected:
  ScratchDir scratch;
  void SetUp() override {
    Image grid(2, 2, Color(0.5f));
    grid.at(0, 0) = Color(1.0f);
    write_text(scratch / "grid.png", bytes_of(encode_png(grid)));
    write_text(scratch / "bright.pfm", bytes_of(encode_pfm(Image(2, 1, Color(3.0f)))));
  }
  SceneDescription load(const std::string& materials, const std::string& shapes = "[]",
                        const std::string& extra = "") {
    write_text(scratch / "scene.json", R"({"camera": {"position": [0,0,0], "look_at": [0,0,1], "vfov": 40},
      "materials": )" + materials + R"(, "shapes": )" + shapes + extra + "}");
    return load_scene(scratch / "scene.json");
  }
  std::string failure(const std::string& materials, const std::string& shapes = "[]", const std::string& extra = "") {
    return error_message([&] { load(materials, shapes, extra); });
  }
};

TEST_F(TexturedScene, TexturesReadWithTheirModesAndMean) {
  const SceneDescription s = load(R"({"a": {"albedo": {"file": "grid.png", "wrap": "clamp", "filter": "nearest"}},
      "b": {"type": "phong", "albedo": [0, 0, 0], "specular": {"file": "grid.png", "encoding": "linear"}},
      "c": {"type": "microfacet", "specular": {"file": "grid.png"}}})");
  const Material& a = s.materials[0];
  ASSERT_TRUE(a.albedo_texture);
  EXPECT_EQ(a.albedo_texture->wrap, TextureWrap::clamp);
  EXPECT_EQ(a.albedo_texture->filter, TextureFilter::nearest);
  const float half = decode_texel(188, TexelEncoding::srgb);  // 0.5 linear is sRGB code 188
  EXPECT_FLOAT_EQ(a.albedo.r, (1.0f + 3.0f * half) / 4.0f) << "the constant is the texture's mean";
  EXPECT_EQ(a.albedo_texture->largest, Color(1.0f));
  const Material& b = s.materials[1];
  ASSERT_TRUE(b.specular_texture);
  EXPECT_EQ(b.specular_texture->texels->at(1, 1), Color(188.0f / 255.0f)) << "data: codes / 255";
  EXPECT_NE(b.specular_texture->texels, a.albedo_texture->texels) << "read once per encoding";
  EXPECT_EQ(s.materials[2].specular_texture->texels, a.albedo_texture->texels) << "the same file and encoding: shared";
  EXPECT_EQ(b.specular_texture->wrap, TextureWrap::repeat) << "the default";
  EXPECT_EQ(b.specular_texture->filter, TextureFilter::bilinear) << "the default";
  EXPECT_TRUE(s.materials[2].specular_texture);
}

TEST_F(TexturedScene, TextureCoordinatesOfTrianglesAndQuads) {
  const SceneDescription s = load(R"({"m": {}})", R"([
      {"type": "triangle", "material": "m", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "uvs": [[0,0],[2,0],[0,2]]},
      {"type": "quad", "material": "m", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}])");
  EXPECT_EQ(std::get<Triangle>(s.shapes[0].geometry).uvs[1], Vec2(2.0f, 0.0f));
  const Quad& q = std::get<Quad>(s.shapes[1].geometry);
  EXPECT_EQ(q.uvs[0], Vec2(0.0f, 0.0f));
  EXPECT_EQ(q.uvs[2], Vec2(1.0f, 1.0f));
  EXPECT_EQ(q.uvs[3], Vec2(0.0f, 1.0f)) << "the default is the unit square, corner by corner";
}

TEST_F(TexturedScene, EnvironmentFromAFileOrAConstant) {
  SceneDescription s = load(R"({"m": {}})", "[]", R"(, "environment": {"file": "bright.pfm", "scale": 2, "rotation": 90})");
  ASSERT_TRUE(s.environment);
  ASSERT_TRUE(s.environment->image);
  EXPECT_EQ(s.environment->image->at(0, 0), Color(3.0f));
  EXPECT_EQ(s.environment->scale, Color(2.0f));
  EXPECT_EQ(s.environment->rotation_degrees, 90.0f);
  s = load(R"({"m": {}})", "[]", R"(, "environment": {"radiance": [1, 2, 3]})");
  ASSERT_TRUE(s.environment);
  EXPECT_FALSE(s.environment->image);
  EXPECT_EQ(s.environment->scale, Color(1.0f, 2.0f, 3.0f));
}

TEST_F(TexturedScene, BadTexturesAndEnvironmentsFailWithOneLine) {
  const std::string scene = (scratch / "scene.json").string();
  auto expect = [&](const std::string& message, const std::string& fragment) {
    EXPECT_EQ(message.rfind(scene + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message << "\n  expected: " << fragment;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  expect(failure(R"({"m": {"albedo": {"file": "nowhere.png"}}})"), "/materials/m/albedo/file: " + (scratch / "nowhere.png").string());
  expect(failure(R"({"m": {"albedo": {"file": "grid.png", "wrap": "mirror"}}})"), "/materials/m/albedo/wrap: unknown wrap mode 'mirror'");
  expect(failure(R"({"m": {"albedo": {"file": "grid.png", "filter": "cubic"}}})"), "unknown texture filter 'cubic'");
  expect(failure(R"({"m": {"albedo": {"file": "grid.png", "encoding": "gamma"}}})"), "unknown encoding 'gamma'");
  expect(failure(R"({"m": {"albedo": {"file": "bright.pfm"}}})"), "bright.pfm: a texel is above 1, where albedo (more than 1 creates energy) must be in [0, 1]");
  expect(failure(R"({"m": {"albedo": {"file": "grid.png"}, "checker": {"albedo": [1,1,1], "size": 1}}})"),
         "/materials/m/checker: a material has a checker or an albedo texture, not both");
  expect(failure(R"({"m": {"type": "phong", "albedo": {"file": "grid.png"}, "specular": [0.1, 0.1, 0.1]}})"),
         "/materials/m: albedo + specular exceeds 1");
  expect(failure(R"({"m": {}})", R"([{"type": "quad", "material": "m", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "uvs": [[0,0]]}])"),
         "/shapes/0/uvs: expected 4 texture coordinates");
  expect(failure(R"({"m": {}})", R"([{"type": "triangle", "material": "m", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "uvs": [[0,0],[1,0],[0,1e9]]}])"),
         "/shapes/0/uvs/2/1: texture coordinate must be in");
  expect(failure(R"({"m": {}})", "[]", R"(, "environment": {"file": "nowhere.hdr"})"), "/environment/file: ");
  expect(failure(R"({"m": {}})", "[]", R"(, "environment": {})"), "/environment: give either 'file' (an image) or 'radiance'");
  expect(failure(R"({"m": {}})", "[]", R"(, "environment": {"radiance": [1,1,1], "file": "bright.pfm"})"), "give either");
  expect(failure(R"({"m": {}})", "[]", R"(, "environment": {"radiance": [1,1,1], "scale": 2})"), "/environment/scale: ");
  expect(failure(R"({"m": {}})", "[]", R"(, "background": [1,1,1], "environment": {"radiance": [1,1,1]})"),
         "/environment: a scene has a background or an environment, not both");
  expect(failure(R"({"m": {}})", "[]", R"(, "environment": {"radiance": [1,-1,1]})"), "/environment/radiance/1: ");
}

}  // namespace
}  // namespace rt
