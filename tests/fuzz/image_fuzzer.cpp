// libFuzzer target: the texture and environment-map reader (stb_image for PNG, JPEG, BMP, TGA and
// Radiance HDR; the PFM reader) on arbitrary bytes, framed as image_input.h says. An image either
// decodes or is refused with InputError; any other exception, a crash, a leak or a sanitizer report
// is a bug.
#include "common/error.h"
#include "fuzz/image_input.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    rt::fuzzing::decode_image_input(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const rt::InputError&) {
  }
  return 0;
}
