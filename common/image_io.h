// Reading and writing images. The file ending picks the format (docs/design.md):
//   .png  8-bit, through the display transform (common/display_transform.h: exposure, tone curve,
//         sRGB or gamma; by default clamped to [0, 1] and sRGB-encoded), for looking at;
//   .pfm  linear 32-bit float RGB per the PFM spec: little-endian (scale -1), bottom row first
//         (for measuring);
//   .exr  linear OpenEXR (through Debian's tinyexr), 32-bit float or 16-bit half channels R, G, B,
//         ZIP-compressed, for HDR viewers and compositing.
// Linear formats are never tone-mapped: they hold the renderer's radiance as it is.
// Writers are atomic (common/file_io.h); every failure throws InputError naming the file.
#pragma once

#include "common/display_transform.h"
#include "common/image.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rt {

enum class ImageFormat { png, pfm, exr };

// The format named by the file ending; throws UsageError for any other ending.
ImageFormat image_format_for(const std::filesystem::path& path);

// How the formats that need a choice encode: a PNG's display transform, an EXR's precision.
struct ImageEncoding {
  DisplayTransform display;
  bool exr_half = false;  // 16-bit half floats (3 significant decimal digits, up to 65504)
};

void write_image(const std::filesystem::path& path, const Image& image, const ImageEncoding& encoding = {});
// The same for a program's output, with a warning on stderr, as `program`, for every value that
// its encoding cannot hold and writes changed (a half float's range).
void write_output_image(const char* program, const std::filesystem::path& path, const Image& image,
                        const ImageEncoding& encoding);

// The largest finite half float (IEEE 754 binary16). From 65520 on, a value rounds to infinity, so
// a half EXR holds this in place of anything larger in magnitude: no file ever holds an infinity.
inline constexpr float kLargestHalf = 65504.0f;
// How many channel values of `image` lie beyond +-kLargestHalf.
std::uint64_t count_beyond_half(const Image& image);

std::vector<char> encode_png(const Image& image, const DisplayTransform& display = {});
// With `half`, values beyond +-kLargestHalf are written as +-kLargestHalf.
std::vector<char> encode_exr(const Image& image, bool half);
// Reads the R, G and B channels (float or half; any others ignored) of a scanline OpenEXR image from
// its bytes; `name` names it in messages. For tests and tools: it trusts the file's size.
Image decode_exr(const std::string& bytes, const std::string& name);
std::vector<char> encode_pfm(const Image& image);
// One channel ("Pf"), `values` row by row from the top: a sample-count image (common/sample_batch.h).
std::vector<char> encode_pfm_grey(int width, int height, const std::vector<float>& values);

// Reads colour ("PF") and greyscale ("Pf", returned grey: r = g = b) PFM files of either byte
// order, up to 65536 pixels a side.
Image read_pfm(const std::filesystem::path& path);
// The same from the file's bytes already in memory; `name` names it in messages.
Image decode_pfm(const std::string& bytes, const std::string& name);
// A PFM file's header, read and checked (magic, size, scale) without touching its pixels, so that a
// caller may refuse the size before anything is decoded. Throws InputError as decode_pfm does.
struct PfmHeader {
  int width, height, channels;
  bool little_endian;
  size_t data_offset;  // where the floats start
};
PfmHeader read_pfm_header(const std::string& bytes, const std::string& name);
inline constexpr std::uintmax_t kMaxPfmFileBytes = std::uintmax_t(1) << 36;  // 65536^2 RGB floats


}  // namespace rt
