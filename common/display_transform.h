// From radiance to a picture: what happens to a linear render on its way into an 8-bit image, and
// only there (PNG); linear outputs (PFM, EXR, sample batches) keep the numbers the renderer made.
//
// The numbers are linear radiance in the sRGB / Rec. 709 primaries (ITU-R BT.709) with a D65 white:
// the renderer's R, G, B are those primaries' amounts, never gamma-encoded. A PNG holds sRGB-encoded
// bytes (IEC 61966-2-1), which a display turns back into light. Between the two, in this order:
//   1. exposure: multiply by 2^stops (a camera's exposure compensation; one stop doubles);
//   2. tone curve: map [0, inf) into [0, 1]: clamp (the default), Reinhard's extended curve or an
//      ACES filmic fit;
//   3. transfer curve: sRGB's (the default) or a plain power 1/gamma;
//   4. round to the nearest of 256 codes.
// docs/display.md answers the lecture's question "Is the radiance of a pixel the color of a pixel?"
// with one HDR render under each of these.
#pragma once

#include "common/color.h"
#include "common/math.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

namespace rt {

enum class ToneCurve { clamp, reinhard, aces };
enum class TransferCurve { srgb, gamma };
inline constexpr std::array<std::pair<ToneCurve, const char*>, 3> kToneCurveNames{{
    {ToneCurve::clamp, "clamp"},
    {ToneCurve::reinhard, "reinhard"},
    {ToneCurve::aces, "aces"},
}};

struct DisplayTransform {
  float exposure_stops = 0.0f;
  ToneCurve tone = ToneCurve::clamp;
  float white = 4.0f;  // Reinhard's L_white: the luminance (after exposure) that maps to 1
  TransferCurve transfer = TransferCurve::srgb;
  float gamma = 2.2f;  // the power-law transfer's exponent
};

// Reinhard, Stark, Shirley and Ferwerda, "Photographic Tone Reproduction for Digital Images",
// SIGGRAPH 2002, eq. 4: L_d = L (1 + L / L_white^2) / (1 + L). Monotone for L >= 0, 0 at 0, and
// exactly 1 at L = L_white (beyond it the result is clamped to 1): "burns out" only above white.
inline float reinhard_extended(float luminance_in, float white) {
  return luminance_in * (1.0f + luminance_in / (white * white)) / (1.0f + luminance_in);
}

// Narkowicz's fit of the ACES reference rendering transform's filmic curve ("ACES Filmic Tone
// Mapping Curve", 2016), applied per channel to 0.6 x (his exposure match to the reference):
//   f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),   x = 0.6 v.
// 0 at 0, monotone, a toe below 0.1 and a shoulder; it reaches 1 at v = kAcesWhite and tends to
// 2.51 / 2.43 > 1, so the result is clamped to 1 from there on.
inline float aces_filmic(float v) {
  const float x = 0.6f * v;
  return x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
}
// Where f = 1: 0.6 v solves 0.08 x^2 - 0.56 x - 0.14 = 0, x = (0.56 + sqrt(0.56^2 + 4 0.08 0.14)) / 0.16.
inline const float kAcesWhite = float((0.56 + std::sqrt(0.56 * 0.56 + 4.0 * 0.08 * 0.14)) / 0.16 / 0.6);

// Steps 1 and 2: exposed and tone-mapped linear values, each channel in [0, 1] (NaN to 0).
inline Color tone_map(Color c, const DisplayTransform& t) {
  c *= std::exp2(t.exposure_stops);
  switch (t.tone) {
    case ToneCurve::clamp: break;
    case ToneCurve::reinhard: {
      // On luminance, as the paper does, so hues keep their ratios until a channel clips.
      const float y = luminance(c);
      if (y > 0.0f) c *= reinhard_extended(y, t.white) / y;
      break;
    }
    case ToneCurve::aces: c = Color(aces_filmic(c.r), aces_filmic(c.g), aces_filmic(c.b)); break;
  }
  auto unit = [](float v) { return v > 0.0f ? std::min(v, 1.0f) : 0.0f; };
  return Color(unit(c.r), unit(c.g), unit(c.b));
}

// Step 3 for one channel in [0, 1].
inline float transfer_encode(float v, const DisplayTransform& t) {
  return t.transfer == TransferCurve::srgb ? srgb_encode(v) : std::pow(v, 1.0f / t.gamma);
}

// All four steps: the 8-bit codes of one pixel.
inline std::array<std::uint8_t, 3> display_bytes(const Color& linear, const DisplayTransform& t) {
  const Color c = tone_map(linear, t);
  auto code = [&](float v) { return std::uint8_t(std::lround(255.0f * transfer_encode(v, t))); };
  return {code(c.r), code(c.g), code(c.b)};
}

}  // namespace rt
