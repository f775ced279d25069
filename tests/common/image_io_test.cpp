#include "common/color.h"
#include "common/error.h"
#include "common/image_io.h"

#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <sys/resource.h>

#include <csignal>
#include <cstring>

namespace rt {
namespace {

using testing::ScratchDir;

Image test_pattern() {
  Image image(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) image.at(x, y) = Color(float(x), float(y), 0.25f * float(x + 3 * y));
  image.at(2, 1) = Color(1e-30f, 3.4e38f, -2.5f);  // extremes survive a linear float format
  return image;
}

TEST(SrgbCurve, KnownValues) {
  EXPECT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_EQ(srgb_encode(1.0f), 1.0f);
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.04045f, 1e-5f);  // where the two pieces meet
  EXPECT_NEAR(srgb_encode(0.001f), 0.01292f, 1e-7f);      // linear segment, slope 12.92
  EXPECT_NEAR(srgb_encode(0.18f), 0.46135f, 1e-4f);       // mid grey
  EXPECT_NEAR(srgb_encode(0.5f), 0.73536f, 1e-4f);        // not 0.5^(1/2.2) = 0.72974
  EXPECT_EQ(srgb_to_byte(0.5f), 188);
  // Every 8-bit code survives decode-then-encode.
  for (int code = 0; code < 256; ++code) EXPECT_EQ(srgb_to_byte(srgb_decode(code / 255.0f)), code);
}

TEST(SrgbCurve, ClampsAndMapsNanToBlack) {
  EXPECT_EQ(srgb_encode(-1.0f), 0.0f);
  EXPECT_EQ(srgb_encode(7.0f), 1.0f);
  EXPECT_EQ(srgb_encode(std::nanf("")), 0.0f);
  EXPECT_EQ(srgb_to_byte(kInfinity), 255);
}

TEST(SrgbCurve, DecodeInvertsEncode) {
  for (float v = 0.0f; v <= 1.0f; v += 1.0f / 1024.0f)
    EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 2e-6f + 1e-5f * v);
}

TEST(Pfm, RoundTripIsBitExact) {
  ScratchDir dir;
  const Image image = test_pattern();
  write_image(dir / "a.pfm", image);
  EXPECT_EQ(read_pfm(dir / "a.pfm"), image);
}

TEST(Pfm, LayoutFollowsTheSpec) {
  // Header "PF\n3 2\n-1.0\n" (negative scale: little-endian), then the BOTTOM row first.
  const Image image = test_pattern();
  const std::vector<char> bytes = encode_pfm(image);
  const std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 3 * 2 * 3 * sizeof(float));
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + long(header.size())), header);
  float first[3];
  std::memcpy(first, bytes.data() + header.size(), sizeof first);
  EXPECT_EQ(Color(first[0], first[1], first[2]), image.at(0, 1)) << "first stored pixel is bottom-left";
}

TEST(Pfm, ReadsBigEndianAndGreyscale) {
  ScratchDir dir;
  // 2x1 greyscale, big-endian (positive scale): bottom row = the only row.
  std::string text = "Pf\n2 1\n1.0\n";
  for (float v : {0.5f, 2.0f}) {
    const auto bits = __builtin_bswap32(std::bit_cast<std::uint32_t>(v));
    text.append(reinterpret_cast<const char*>(&bits), 4);
  }
  testing::write_text(dir / "g.pfm", text);
  const Image image = read_pfm(dir / "g.pfm");
  ASSERT_EQ(image.width(), 2);
  EXPECT_EQ(image.at(0, 0), Color(0.5f));
  EXPECT_EQ(image.at(1, 0), Color(2.0f));
}

TEST(Pfm, BadFilesGiveInputErrorsNamingTheFile) {
  ScratchDir dir;
  testing::write_text(dir / "truncated.pfm", "PF\n4 4\n-1.0\n1234");
  testing::write_text(dir / "nonsense.pfm", "P6\n4 4\n255\n");
  testing::write_text(dir / "huge.pfm", "PF\n999999999 999999999\n-1.0\n");
  // A size the reader accepts, but far more than the file holds: refused before 43 GB are allocated.
  testing::write_text(dir / "claims.pfm", "PF\n60000 60000\n-1.0\n1234");
  for (const char* name : {"truncated.pfm", "nonsense.pfm", "huge.pfm", "claims.pfm", "missing.pfm"}) {
    try {
      read_pfm(dir / name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

TEST(Png, WritesAValidPngOfTheRightSize) {
  ScratchDir dir;
  write_image(dir / "a.png", Image(5, 3, Color(0.5f)));
  const std::string bytes = testing::read_text(dir / "a.png");
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR width and height, big-endian, at bytes 16..23.
  EXPECT_EQ(bytes[19], 5);
  EXPECT_EQ(bytes[23], 3);
}

TEST(Exr, FloatRoundTripIsBitExact) {
  ScratchDir dir;
  const Image image = test_pattern();
  write_image(dir / "a.exr", image);
  const std::string bytes = testing::read_text(dir / "a.exr");
  EXPECT_EQ(bytes.substr(0, 4), std::string("\x76\x2f\x31\x01", 4)) << "the OpenEXR magic number";
  EXPECT_EQ(decode_exr(bytes, "a.exr"), image);
}

// Half floats keep 11 significant bits: every value comes back within half an ulp of half
// (2^-11 relative).
TEST(Exr, HalfRoundTripKeepsElevenBits) {
  ScratchDir dir;
  Image image(64, 3);
  for (int x = 0; x < 64; ++x) image.at(x, 0) = image.at(x, 1) = image.at(x, 2) = Color(std::ldexp(1.37f, x / 4 - 8));
  ImageEncoding encoding;
  encoding.exr_half = true;
  write_image(dir / "h.exr", image, encoding);
  const std::string bytes = testing::read_text(dir / "h.exr");
  const Image back = decode_exr(bytes, "h.exr");
  ASSERT_EQ(back.width(), 64);
  for (size_t i = 0; i < image.pixel_count(); ++i)
    ASSERT_NEAR(back.pixels()[i].r, image.pixels()[i].r, image.pixels()[i].r * 0x1p-11f) << i;
  write_image(dir / "f.exr", image);
  EXPECT_LT(bytes.size(), testing::read_text(dir / "f.exr").size()) << "half the bytes per channel";
}

// Found by trying: --exr-half wrote +inf for radiance above 65504, half's largest value. Such
// values are written as +-65504 and counted for the warning (from 65520 on, half's rounding gives
// infinity); 65504 itself is held exactly and not counted, the next float above it is.
TEST(Exr, HalfClampsWhatItCannotHoldInsteadOfWritingInfinity) {
  ScratchDir dir;
  const float above = std::nextafter(kLargestHalf, 1e30f);
  const std::vector<float> values = {kLargestHalf, above, 1e10f, 3.4e38f, -kLargestHalf, -above, -3.4e38f, 1.0f};
  Image image(int(values.size()), 1);
  for (size_t i = 0; i < values.size(); ++i) image.at(int(i), 0) = Color(values[i], 1.0f, -values[i]);
  EXPECT_EQ(count_beyond_half(image), 10u);  // 5 of the 8 values, each in r and in b
  ImageEncoding encoding;
  encoding.exr_half = true;
  write_image(dir / "h.exr", image, encoding);
  const Image back = decode_exr(testing::read_text(dir / "h.exr"), "h.exr");
  for (size_t i = 0; i < values.size(); ++i) {
    const float expected = std::clamp(values[i], -kLargestHalf, kLargestHalf);
    EXPECT_EQ(back.at(int(i), 0).r, expected) << values[i];
    EXPECT_EQ(back.at(int(i), 0).b, -expected) << values[i];
  }
  write_image(dir / "f.exr", image);  // 32-bit floats hold them all as they are
  EXPECT_EQ(decode_exr(testing::read_text(dir / "f.exr"), "f.exr"), image);
}

TEST(Exr, ABrokenFileIsAnInputErrorNamingIt) {
  EXPECT_THROW(decode_exr("not an exr", "x.exr"), InputError);
  try {
    decode_exr(std::string("\x76\x2f\x31\x01\x02\0\0\0", 8), "broken.exr");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.exr"), std::string::npos);
  }
}

// A PNG goes through the display transform; the linear formats never do.
TEST(ImageFiles, OnlyThePngIsToneMapped) {
  ScratchDir dir;
  const Image image(4, 4, Color(0.25f));
  ImageEncoding bright;
  bright.display.exposure_stops = 2.0f;
  write_image(dir / "a.pfm", image, bright);
  write_image(dir / "a.exr", image, bright);
  EXPECT_EQ(read_pfm(dir / "a.pfm"), image);
  EXPECT_EQ(decode_exr(testing::read_text(dir / "a.exr"), "a.exr"), image);
  EXPECT_NE(encode_png(image, bright.display), encode_png(image));
  EXPECT_EQ(encode_png(Image(4, 4, Color(1.0f))), encode_png(image, bright.display)) << "0.25 x 2^2 = 1";
}

TEST(ImageFiles, FormatComesFromTheEnding) {
  EXPECT_EQ(image_format_for("x.png"), ImageFormat::png);
  EXPECT_EQ(image_format_for("x.exr"), ImageFormat::exr);
  EXPECT_EQ(image_format_for("dir.d/x.pfm"), ImageFormat::pfm);
  EXPECT_THROW(image_format_for("x.jpg"), UsageError);
  EXPECT_THROW(image_format_for("png"), UsageError);
}

TEST(ImageFiles, FailedWriteLeavesNoFileAndKeepsTheOldOne) {
  ScratchDir dir;
  EXPECT_THROW(write_image(dir / "no-such-dir" / "a.png", Image(2, 2)), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "no-such-dir"));

  // Make the write itself fail, in a way that holds for root too (permissions do not stop root):
  // a file size limit of 16 bytes, less than the PFM, with SIGXFSZ ignored so write(2) fails.
  write_image(dir / "keep.pfm", Image(1, 1, Color(3.0f)));
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit tiny = saved;
  tiny.rlim_cur = 16;
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &tiny), 0);
  EXPECT_THROW(write_image(dir / "keep.pfm", Image(1, 1, Color(4.0f))), InputError);
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, previous);
  EXPECT_EQ(read_pfm(dir / "keep.pfm").at(0, 0), Color(3.0f)) << "the old file must survive intact";
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1) << "the failed write's temporary file must be gone";
}

TEST(ImageFiles, AtomicWriteLeavesNoTemporaryFiles) {
  ScratchDir dir;
  write_image(dir / "a.png", Image(4, 4));
  write_image(dir / "a.png", Image(8, 8));
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace rt
