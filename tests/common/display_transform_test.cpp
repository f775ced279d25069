// The display transform (common/display_transform.h): exposure, the tone curves and the transfer
// curves, each at the values the header promises, and the default is the PNG path as it always
// was (clamp, then the sRGB curve).
#include "common/display_transform.h"
#include "common/image_io.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

TEST(DisplayTransform, SrgbCurveMeetsAtItsBreakpointAndInvertsThere) {
  // The two pieces agree at the breakpoint: 12.92 x 0.0031308 = 1.055 x 0.0031308^(1/2.4) - 0.055.
  const float linear_piece = 12.92f * 0.0031308f;
  const float power_piece = 1.055f * std::pow(0.0031308f, 1.0f / 2.4f) - 0.055f;
  EXPECT_NEAR(linear_piece, power_piece, 2e-6f);
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.04045f, 1e-6f);
  EXPECT_NEAR(srgb_encode(std::nextafter(0.0031308f, 1.0f)), 0.04045f, 1e-6f) << "no step across the breakpoint";
  EXPECT_NEAR(srgb_decode(0.04045f), 0.0031308f, 1e-8f);
  EXPECT_EQ(srgb_decode(0.0f), 0.0f);
  EXPECT_NEAR(srgb_decode(1.0f), 1.0f, 1e-7f);
}

TEST(DisplayTransform, TheDefaultIsClampThenSrgb) {
  const DisplayTransform plain;
  for (float v = -0.5f; v < 3.0f; v += 1.0f / 997.0f) {
    const auto bytes = display_bytes(Color(v, 0.5f * v, 2.0f * v), plain);
    ASSERT_EQ(bytes[0], srgb_to_byte(v)) << v;
    ASSERT_EQ(bytes[1], srgb_to_byte(0.5f * v)) << v;
    ASSERT_EQ(bytes[2], srgb_to_byte(2.0f * v)) << v;
  }
  EXPECT_EQ(display_bytes(Color(std::nanf(""), kInfinity, -kInfinity), plain), (std::array<std::uint8_t, 3>{0, 255, 0}));
}

TEST(DisplayTransform, EachStopOfExposureDoublesTheRadiance) {
  DisplayTransform t;
  for (const float stops : {-3.0f, -1.0f, 0.0f, 1.0f, 2.0f}) {
    t.exposure_stops = stops;
    EXPECT_FLOAT_EQ(tone_map(Color(0.01f), t).r, 0.01f * std::exp2(stops)) << stops;
  }
  t.exposure_stops = 1.0f;
  EXPECT_EQ(tone_map(Color(0.125f), t).r, 0.25f) << "one stop is exactly a factor 2";
}

TEST(DisplayTransform, PowerLawGammaIsTheInversePower) {
  DisplayTransform t;
  t.transfer = TransferCurve::gamma;
  t.gamma = 2.2f;
  EXPECT_FLOAT_EQ(transfer_encode(0.5f, t), std::pow(0.5f, 1.0f / 2.2f));
  EXPECT_EQ(transfer_encode(0.0f, t), 0.0f);
  EXPECT_EQ(transfer_encode(1.0f, t), 1.0f);
  // Near black the two curves part: sRGB's linear toe is far darker than the pure power.
  EXPECT_LT(srgb_encode(0.001f), transfer_encode(0.001f, t) / 2.0f);
}

// Every curve maps 0 to 0, is monotone, and reaches 1 at its white point: Reinhard's at L_white
// (then clamped), ACES's at kAcesWhite (then clamped), the clamp at 1.
TEST(DisplayTransform, ToneCurvesAreMonotoneFromZeroToTheirWhitePoint) {
  for (const auto& [tone, name] : kToneCurveNames) {
    DisplayTransform t;
    t.tone = tone;
    EXPECT_EQ(tone_map(Color(0.0f), t).r, 0.0f) << name;
    float last = 0.0f;
    for (float v = 1e-4f; v < 50.0f; v *= 1.01f) {
      const float mapped = tone_map(Color(v), t).g;
      ASSERT_GE(mapped, last) << name << " at " << v;
      ASSERT_LE(mapped, 1.0f) << name << " at " << v;
      last = mapped;
    }
    EXPECT_EQ(last, 1.0f) << name << ": bright enough light is white";
  }
  EXPECT_NEAR(reinhard_extended(4.0f, 4.0f), 1.0f, 1e-6f);
  EXPECT_LT(reinhard_extended(3.9f, 4.0f), 1.0f);
  // Far below white it is the simple curve L / (1 + L), up to the factor 1 + L / L_white^2.
  EXPECT_NEAR(reinhard_extended(0.01f, 4.0f), 0.01f / 1.01f, 0.01f / 1.01f * 0.01f / 16.0f * 1.01f);
  EXPECT_NEAR(aces_filmic(kAcesWhite), 1.0f, 1e-5f);
  EXPECT_LT(aces_filmic(0.98f * kAcesWhite), 1.0f);
  EXPECT_NEAR(aces_filmic(1e6f), 2.51f / 2.43f, 1e-4f) << "the fit's asymptote, above 1: hence the clamp";
}

TEST(DisplayTransform, ReinhardActsOnLuminanceAndKeepsHue) {
  DisplayTransform t;
  t.tone = ToneCurve::reinhard;
  const Color in(0.3f, 0.6f, 0.15f), out = tone_map(in, t);
  const float y = luminance(in);
  EXPECT_NEAR(luminance(out), reinhard_extended(y, t.white), 1e-6f);
  EXPECT_NEAR(out.r / out.g, in.r / in.g, 1e-5f);
  EXPECT_NEAR(out.b / out.g, in.b / in.g, 1e-5f);
}

}  // namespace
}  // namespace rt
