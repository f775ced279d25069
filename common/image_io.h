// Reading and writing images. The file ending picks the format (docs/design.md):
//   .png  sRGB-encoded 8-bit, clamped to [0, 1] (for looking at);
//   .pfm  linear 32-bit float RGB per the PFM spec: little-endian (scale -1), bottom row first
//         (for measuring).
// Writers are atomic (common/file_io.h); every failure throws InputError naming the file.
#pragma once

#include "common/image.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rt {

enum class ImageFormat { png, pfm };

// The format named by the file ending; throws UsageError for any other ending.
ImageFormat image_format_for(const std::filesystem::path& path);

void write_image(const std::filesystem::path& path, const Image& image);

std::vector<char> encode_png(const Image& image);
std::vector<char> encode_pfm(const Image& image);
// One channel ("Pf"), `values` row by row from the top: a sample-count image (common/sample_batch.h).
std::vector<char> encode_pfm_grey(int width, int height, const std::vector<float>& values);

// Reads colour ("PF") and greyscale ("Pf", returned grey: r = g = b) PFM files of either byte
// order, up to 65536 pixels a side.
Image read_pfm(const std::filesystem::path& path);
// The same from the file's bytes already in memory; `name` names it in messages.
Image decode_pfm(const std::string& bytes, const std::string& name);
inline constexpr std::uintmax_t kMaxPfmFileBytes = std::uintmax_t(1) << 36;  // 65536^2 RGB floats


}  // namespace rt
