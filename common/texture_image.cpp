#include "common/texture_image.h"

#include "common/color.h"
#include "common/error.h"
#include "common/file_io.h"
#include "common/image_io.h"
#include "common/memory_limit.h"

#include <stb_image.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

namespace rt {
namespace {

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

// The size, checked before any pixel is decoded: the format's limit, then this process's memory.
void check_size(long long width, long long height, const std::string& name) {
  if (width <= 0 || height <= 0 || width > kMaxTexturePixels || height > kMaxTexturePixels ||
      width * height > kMaxTexturePixels)
    throw InputError(name + ": image of " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels; a texture may have at most 8192x8192");
  const MemoryLimit limit = memory_limit();
  const double needed = double(width) * double(height) * double(kTextureDecodeBytesPerPixel);
  if (needed > double(limit.bytes))
    throw InputError(name + ": a " + std::to_string(width) + "x" + std::to_string(height) + " texture needs " +
                     binary_size(needed) + " of memory to decode, and " + limit.describe());
}

// A PNG's size from its IHDR chunk, which the format puts first: stb_image's own reading refuses a
// PNG of more than 2^30 bytes of pixels before saying its size, and then names no reason at all.
std::optional<std::pair<long long, long long>> png_size(const std::string& bytes) {
  static const char kSignature[] = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 24 || bytes.compare(0, 8, kSignature, 8) != 0 || bytes.compare(12, 4, "IHDR") != 0) return {};
  auto big_endian = [&](size_t at) {
    long long v = 0;
    for (size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  return std::pair(big_endian(16), big_endian(20));
}

// stb_image's reason for a failure, in words where it gave a code.
std::string stb_reason() {
  const std::string reason = stbi_failure_reason() ? stbi_failure_reason() : "no reason given";
  if (reason == "outofmem") return "out of memory while decoding it, and " + memory_limit().describe();
  return reason;
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
    const PfmHeader header = read_pfm_header(bytes, name);
    check_size(header.width, header.height, name);
    image = decode_pfm(bytes, name);
  } else {
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = int(std::min<size_t>(bytes.size(), size_t(1) << 30));
    if (const auto size = png_size(bytes)) check_size(size->first, size->second, name);
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(data, length, &width, &height, &channels))
      throw InputError(name + ": not an image stb_image can read (" + stb_reason() + ")");
    check_size(width, height, name);
    image = Image(width, height);
    if (stbi_is_hdr_from_memory(data, length)) {
      const std::unique_ptr<float, StbFree> texels(stbi_loadf_from_memory(data, length, &width, &height, &channels, 3));
      if (!texels) throw InputError(name + ": broken HDR image (" + stb_reason() + ")");
      for (size_t i = 0; i < image.pixel_count(); ++i)
        image.pixels()[i] = Color(texels.get()[3 * i], texels.get()[3 * i + 1], texels.get()[3 * i + 2]);
    } else {
      const std::unique_ptr<stbi_uc, StbFree> codes(stbi_load_from_memory(data, length, &width, &height, &channels, 3));
      if (!codes) throw InputError(name + ": broken image (" + stb_reason() + ")");
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
  // The size in a PFM's or PNG's header is checked before the file is read whole: a PFM texture of
  // 9000^2 pixels is a gigabyte.
  const std::string name = path.string(), head = read_input_file(path, "image file", kMaxTextureFileBytes, 64);
  if (path.extension() == ".pfm") {
    const PfmHeader header = read_pfm_header(head, name);
    check_size(header.width, header.height, name);
  } else if (const auto size = png_size(head)) {
    check_size(size->first, size->second, name);
  }
  return decode_texture_image(read_input_file(path, "image file", kMaxTextureFileBytes), name, encoding);
}

}  // namespace rt
