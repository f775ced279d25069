#include "common/image_io.h"

#include "common/color.h"
#include "common/error.h"
#include "common/file_io.h"

#include <stb_image_write.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace rt {
namespace fs = std::filesystem;

ImageFormat image_format_for(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".pfm") return ImageFormat::pfm;
  throw UsageError("output '" + path.string() + "': unknown image format '" + ext +
                   "' (use .png or .pfm)");
}

void write_image(const fs::path& path, const Image& image) {
  const ImageFormat format = image_format_for(path);
  write_file_atomically(path, format == ImageFormat::png ? encode_png(image) : encode_pfm(image));
}

std::vector<char> encode_png(const Image& image) {
  std::vector<std::uint8_t> rgb;
  rgb.reserve(image.pixel_count() * 3);
  for (const Color& c : image.pixels()) {
    rgb.push_back(srgb_to_byte(c.r));
    rgb.push_back(srgb_to_byte(c.g));
    rgb.push_back(srgb_to_byte(c.b));
  }
  std::vector<char> bytes;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<char>*>(context);
    out->insert(out->end(), static_cast<char*>(data), static_cast<char*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width(), image.height(), 3, rgb.data(),
                              image.width() * 3))
    throw InputError("PNG encoding failed");
  return bytes;
}

std::vector<char> encode_pfm(const Image& image) {
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes little-endian");
  std::ostringstream header;
  header << "PF\n" << image.width() << ' ' << image.height() << "\n-1.0\n";
  const std::string head = header.str();
  std::vector<char> bytes(head.begin(), head.end());
  const size_t row_bytes = size_t(image.width()) * 3 * sizeof(float);
  bytes.resize(head.size() + row_bytes * size_t(image.height()));
  char* out = bytes.data() + head.size();
  // PFM stores the BOTTOM row first; our row 0 is the top.
  for (int y = image.height() - 1; y >= 0; --y, out += row_bytes)
    std::memcpy(out, &image.at(0, y), row_bytes);
  return bytes;
}

Image read_pfm(const fs::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open file");
  std::string magic;
  long long width = 0, height = 0;
  double scale = 0.0;
  in >> magic >> width >> height >> scale;
  if (!in || (magic != "PF" && magic != "Pf"))
    throw InputError(name + ": not a PFM file (bad header)");
  if (width <= 0 || height <= 0 || width > (1 << 16) || height > (1 << 16))
    throw InputError(name + ": bad PFM size " + std::to_string(width) + "x" +
                     std::to_string(height));
  if (scale == 0.0 || !std::isfinite(scale)) throw InputError(name + ": bad PFM scale");
  in.get();  // exactly one whitespace character ends the header
  const int channels = magic == "PF" ? 3 : 1;
  const bool file_is_little_endian = scale < 0.0;
  std::vector<float> data(size_t(width) * size_t(height) * size_t(channels));
  in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * sizeof(float)));
  if (in.gcount() != std::streamsize(data.size() * sizeof(float)))
    throw InputError(name + ": PFM data is truncated");
  if (file_is_little_endian != (std::endian::native == std::endian::little))
    for (float& v : data) v = std::bit_cast<float>(__builtin_bswap32(std::bit_cast<std::uint32_t>(v)));

  Image image{int(width), int(height)};
  for (int row = 0; row < image.height(); ++row)
    for (int x = 0; x < image.width(); ++x) {
      const float* p = &data[(size_t(row) * size_t(width) + size_t(x)) * size_t(channels)];
      image.at(x, image.height() - 1 - row) = channels == 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
    }
  return image;
}

}  // namespace rt
