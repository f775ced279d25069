// Reading and writing images. The file ending picks the format (DESIGN.md):
//   .png  sRGB-encoded 8-bit, clamped to [0, 1] (for looking at);
//   .pfm  linear 32-bit float RGB per the PFM spec: little-endian (scale -1), bottom row first
//         (for measuring).
// Writers are atomic (common/file_io.h); every failure throws InputError naming the file.
#pragma once

#include "common/image.h"

#include <filesystem>
#include <vector>

namespace rt {

enum class ImageFormat { png, pfm };

// The format named by the file ending; throws UsageError for any other ending.
ImageFormat image_format_for(const std::filesystem::path& path);

void write_image(const std::filesystem::path& path, const Image& image);

std::vector<char> encode_png(const Image& image);
std::vector<char> encode_pfm(const Image& image);

// Reads colour ("PF") and greyscale ("Pf") PFM files of either byte order.
Image read_pfm(const std::filesystem::path& path);

}  // namespace rt
