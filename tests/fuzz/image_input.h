// The image fuzzer's input, shared with the replay in tests/reliability: the first byte picks the
// name's ending (bit 0: .pfm, else .png) and the encoding (bit 1: linear, else sRGB), so that both
// readers and both decodes run; the rest is the file.
#pragma once

#include "common/texture_image.h"

#include <string>

namespace rt::fuzzing {

inline void decode_image_input(const std::string& input) {
  if (input.empty()) return;
  const auto flags = static_cast<unsigned char>(input[0]);
  decode_texture_image(input.substr(1), (flags & 1) ? "fuzz.pfm" : "fuzz.png",
                       (flags & 2) ? TexelEncoding::linear : TexelEncoding::srgb);
}

}  // namespace rt::fuzzing
