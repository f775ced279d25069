#include "common/texture_image.h"

#include "common/color.h"
#include "common/error.h"
#include "common/file_io.h"
#include "common/image_io.h"

#include <stb_image.h>

#include <array>
#include <cmath>
#include <memory>

namespace rt {
namespace {

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

void check_size(long long width, long long height, const std::string& name) {
  if (width <= 0 || height <= 0 || width * height > kMaxTexturePixels)
    throw InputError(name + ": image of " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels; a texture may have at most 8192x8192");
}

void check_texels(const Image& image, const std::string& name) {
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const Color c = image.at(x, y);
      if (!(is_finite(c) && min_component(c) >= 0.0f))
        throw InputError(name + ": texel (" + std::to_string(x) + ", " + std::to_string(y) +
                         ") is not a finite, non-negative colour");
    }
}

}  // namespace

float decode_texel(std::uint8_t code, TexelEncoding encoding) {
  const float v = float(code) / 255.0f;
  return encoding == TexelEncoding::srgb ? srgb_decode(v) : v;
}

Image decode_texture_image(const std::string& bytes, const std::string& name, TexelEncoding encoding) {
  Image image;
  if (std::filesystem::path(name).extension() == ".pfm") {
    image = decode_pfm(bytes, name);
    check_size(image.width(), image.height(), name);
  } else {
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = int(std::min<size_t>(bytes.size(), size_t(1) << 30));
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(data, length, &width, &height, &channels))
      throw InputError(name + ": not an image stb_image can read (" + stbi_failure_reason() + ")");
    check_size(width, height, name);
    image = Image(width, height);
    if (stbi_is_hdr_from_memory(data, length)) {
      const std::unique_ptr<float, StbFree> texels(stbi_loadf_from_memory(data, length, &width, &height, &channels, 3));
      if (!texels) throw InputError(name + ": broken HDR image (" + stbi_failure_reason() + ")");
      for (size_t i = 0; i < image.pixel_count(); ++i)
        image.pixels()[i] = Color(texels.get()[3 * i], texels.get()[3 * i + 1], texels.get()[3 * i + 2]);
    } else {
      const std::unique_ptr<stbi_uc, StbFree> codes(stbi_load_from_memory(data, length, &width, &height, &channels, 3));
      if (!codes) throw InputError(name + ": broken image (" + stbi_failure_reason() + ")");
      std::array<float, 256> table;  // every code decoded once
      for (int c = 0; c < 256; ++c) table[size_t(c)] = decode_texel(std::uint8_t(c), encoding);
      for (size_t i = 0; i < image.pixel_count(); ++i)
        image.pixels()[i] = Color(table[codes.get()[3 * i]], table[codes.get()[3 * i + 1]], table[codes.get()[3 * i + 2]]);
    }
  }
  check_texels(image, name);
  return image;
}

Image read_texture_image(const std::filesystem::path& path, TexelEncoding encoding) {
  return decode_texture_image(read_input_file(path, "image file", kMaxTextureFileBytes), path.string(), encoding);
}

}  // namespace rt
