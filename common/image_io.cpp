#include "common/image_io.h"

#include "common/color.h"
#include "common/error.h"
#include "common/file_io.h"

#include <stb_image_write.h>
#include <tinyexr.h>

#include <bit>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rt {
namespace fs = std::filesystem;

namespace {

// `rows` holds `channels` floats per pixel, top row first; PFM stores the BOTTOM row first.
std::vector<char> encode_pfm_rows(int width, int height, int channels, const float* rows) {
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes little-endian");
  std::ostringstream header;
  header << (channels == 3 ? "PF\n" : "Pf\n") << width << ' ' << height << "\n-1.0\n";
  const std::string head = header.str();
  std::vector<char> bytes(head.begin(), head.end());
  const size_t row_floats = size_t(width) * size_t(channels);
  bytes.resize(head.size() + row_floats * sizeof(float) * size_t(height));
  char* out = bytes.data() + head.size();
  for (int y = height - 1; y >= 0; --y, out += row_floats * sizeof(float))
    std::memcpy(out, rows + size_t(y) * row_floats, row_floats * sizeof(float));
  return bytes;
}

}  // namespace

ImageFormat image_format_for(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".pfm") return ImageFormat::pfm;
  if (ext == ".exr") return ImageFormat::exr;
  throw UsageError("output '" + path.string() + "': unknown image format '" + ext +
                   "' (use .png, .pfm or .exr)");
}

void write_image(const fs::path& path, const Image& image, const ImageEncoding& encoding) {
  switch (image_format_for(path)) {
    case ImageFormat::png: write_file_atomically(path, encode_png(image, encoding.display)); break;
    case ImageFormat::pfm: write_file_atomically(path, encode_pfm(image)); break;
    case ImageFormat::exr: write_file_atomically(path, encode_exr(image, encoding.exr_half)); break;
  }
}

void write_output_image(const char* program, const fs::path& path, const Image& image, const ImageEncoding& encoding) {
  if (encoding.exr_half && image_format_for(path) == ImageFormat::exr)
    if (const std::uint64_t beyond = count_beyond_half(image))
      std::fprintf(stderr, "%s: warning: %llu values lie beyond %g, the largest half float, and are written as %g "
                   "(write 32-bit floats without --exr-half to keep them)\n",
                   program, static_cast<unsigned long long>(beyond), double(kLargestHalf), double(kLargestHalf));
  write_image(path, image, encoding);
}

std::uint64_t count_beyond_half(const Image& image) {
  std::uint64_t beyond = 0;
  for (const Color& c : image.pixels())
    for (const float v : {c.r, c.g, c.b}) beyond += std::abs(v) > kLargestHalf ? 1 : 0;
  return beyond;
}

std::vector<char> encode_png(const Image& image, const DisplayTransform& display) {
  std::vector<std::uint8_t> rgb;
  rgb.reserve(image.pixel_count() * 3);
  for (const Color& c : image.pixels())
    for (const std::uint8_t code : display_bytes(c, display)) rgb.push_back(code);
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
  return encode_pfm_rows(image.width(), image.height(), 3, &image.pixels().data()->r);
}

std::vector<char> encode_pfm_grey(int width, int height, const std::vector<float>& values) {
  if (values.size() != size_t(width) * size_t(height)) throw std::invalid_argument("encode_pfm_grey: wrong size");
  return encode_pfm_rows(width, height, 1, values.data());
}

namespace {

// tinyexr reports errors in a string it allocated; this takes it over.
std::string take_exr_error(const char* error) {
  std::string text = error ? error : "unknown error";
  if (error) FreeEXRErrorMessage(error);
  return text;
}

}  // namespace

std::vector<char> encode_exr(const Image& image, bool half) {
  // OpenEXR stores channels as planes; readers expect their names in alphabetical order (B, G, R).
  const size_t n = image.pixel_count();
  std::vector<float> planes[3];
  for (auto& plane : planes) plane.resize(n);
  const float limit = half ? kLargestHalf : std::numeric_limits<float>::max();
  for (size_t i = 0; i < n; ++i) {
    const Color c = glm::clamp(image.pixels()[i], -limit, limit);
    planes[0][i] = c.b, planes[1][i] = c.g, planes[2][i] = c.r;
  }
  unsigned char* plane_pointers[3] = {reinterpret_cast<unsigned char*>(planes[0].data()),
                                      reinterpret_cast<unsigned char*>(planes[1].data()),
                                      reinterpret_cast<unsigned char*>(planes[2].data())};
  EXRImage exr_image;
  InitEXRImage(&exr_image);
  exr_image.images = plane_pointers;
  exr_image.width = image.width();
  exr_image.height = image.height();
  exr_image.num_channels = 3;

  EXRChannelInfo channels[3] = {};
  int pixel_types[3], requested_types[3];
  for (int i = 0; i < 3; ++i) {
    channels[i].name[0] = "BGR"[i];
    pixel_types[i] = TINYEXR_PIXELTYPE_FLOAT;
    requested_types[i] = half ? TINYEXR_PIXELTYPE_HALF : TINYEXR_PIXELTYPE_FLOAT;
  }
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = 3;
  header.channels = channels;
  header.pixel_types = pixel_types;
  header.requested_pixel_types = requested_types;
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

  unsigned char* memory = nullptr;
  const char* error = nullptr;
  const size_t size = SaveEXRImageToMemory(&exr_image, &header, &memory, &error);
  if (size == 0) throw InputError("EXR encoding failed: " + take_exr_error(error));
  std::vector<char> bytes(reinterpret_cast<char*>(memory), reinterpret_cast<char*>(memory) + size);
  std::free(memory);
  return bytes;
}

Image decode_exr(const std::string& bytes, const std::string& name) {
  // Header first, then the image for it (tinyexr's one-call LoadEXRFromMemory leaks a few bytes on
  // every file it refuses, which the sanitizers report).
  const auto* memory = reinterpret_cast<const unsigned char*>(bytes.data());
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, memory, bytes.size()) != TINYEXR_SUCCESS)
    throw InputError(name + ": not an OpenEXR image (no OpenEXR version header)");
  if (version.multipart || version.non_image || version.tiled)
    throw InputError(name + ": a tiled, deep or multi-part OpenEXR image, which this reader does not take");
  EXRHeader header;
  InitEXRHeader(&header);
  const char* error = nullptr;
  if (ParseEXRHeaderFromMemory(&header, &version, memory, bytes.size(), &error) != TINYEXR_SUCCESS) {
    FreeEXRHeader(&header);
    throw InputError(name + ": not a readable OpenEXR image (" + take_exr_error(error) + ")");
  }
  int channel_of[3] = {-1, -1, -1};  // R, G, B
  for (int c = 0; c < header.num_channels; ++c) {
    if (header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF) header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    for (int k = 0; k < 3; ++k)
      if (std::string(header.channels[c].name) == std::string(1, "RGB"[k])) channel_of[k] = c;
  }
  EXRImage image;
  InitEXRImage(&image);
  const int loaded = LoadEXRImageFromMemory(&image, &header, memory, bytes.size(), &error);
  auto release = [&] {
    if (loaded == TINYEXR_SUCCESS) FreeEXRImage(&image);
    FreeEXRHeader(&header);
  };
  if (loaded != TINYEXR_SUCCESS) {
    release();
    throw InputError(name + ": not a readable OpenEXR image (" + take_exr_error(error) + ")");
  }
  for (int k = 0; k < 3; ++k)
    if (channel_of[k] < 0 || header.requested_pixel_types[channel_of[k]] != TINYEXR_PIXELTYPE_FLOAT) {
      release();
      throw InputError(name + ": the OpenEXR image has no float or half channel " + std::string(1, "RGB"[k]));
    }
  Image result(image.width, image.height);
  for (size_t i = 0; i < result.pixel_count(); ++i) {
    const auto channel = [&](int k) { return reinterpret_cast<const float*>(image.images[channel_of[k]])[i]; };
    result.pixels()[i] = Color(channel(0), channel(1), channel(2));
  }
  release();
  return result;
}

Image read_pfm(const fs::path& path) {
  return decode_pfm(read_input_file(path, "PFM image", kMaxPfmFileBytes), path.string());
}

PfmHeader read_pfm_header(const std::string& bytes, const std::string& name) {
  std::istringstream in(bytes);
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
  const std::streamoff data_start = in.tellg();
  if (data_start < 0) throw InputError(name + ": PFM data is truncated");
  return PfmHeader{int(width), int(height), magic == "PF" ? 3 : 1, scale < 0.0, size_t(data_start)};
}

Image decode_pfm(const std::string& bytes, const std::string& name) {
  const PfmHeader header = read_pfm_header(bytes, name);
  const size_t width = size_t(header.width), channels = size_t(header.channels);
  // The header's size is checked against the bytes there are before anything is allocated.
  const size_t floats = width * size_t(header.height) * channels;
  if (bytes.size() - header.data_offset < floats * sizeof(float)) throw InputError(name + ": PFM data is truncated");
  std::vector<float> data(floats);
  std::memcpy(data.data(), bytes.data() + header.data_offset, floats * sizeof(float));
  if (header.little_endian != (std::endian::native == std::endian::little))
    for (float& v : data) v = std::bit_cast<float>(__builtin_bswap32(std::bit_cast<std::uint32_t>(v)));

  Image image{header.width, header.height};
  for (int row = 0; row < image.height(); ++row)
    for (int x = 0; x < image.width(); ++x) {
      const float* p = &data[(size_t(row) * width + size_t(x)) * channels];
      image.at(x, image.height() - 1 - row) = channels == 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
    }
  return image;
}

}  // namespace rt
