// Image files read as textures and environment maps: an 8-bit image (PNG, JPEG, BMP, TGA, through
// Debian's stb_image) is decoded to linear values, by the sRGB curve for colours or by v / 255 for
// data; a Radiance .hdr (stb_image too) and a PFM (common/image_io.h) are linear already. What the
// renderer stores is always the linear RGB image, row 0 at the top.
#pragma once

#include "common/image.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace rt {

// How an 8-bit file's codes map to linear values. Colours (an albedo painted or photographed) are
// sRGB-encoded; data (a roughness map, a normal map) is stored as it is. Float files ignore it.
enum class TexelEncoding { srgb, linear };

// The largest texture accepted: 2^26 pixels (8192 x 8192, 768 MiB as float RGB). The size is read
// from the file's header and checked before any pixel is decoded, against this limit and against
// the memory the process may use (common/memory_limit.h) at kTextureDecodeBytesPerPixel: the float
// image (12 bytes) and the decoder's own buffer (3 bytes for 8-bit codes, 12 for floats).
inline constexpr std::int64_t kMaxTexturePixels = std::int64_t(1) << 26;
inline constexpr std::int64_t kTextureDecodeBytesPerPixel = 24;
// A texture file over this many bytes is refused before it is read.
inline constexpr std::uintmax_t kMaxTextureFileBytes = std::uintmax_t(1) << 30;

// Throws InputError("FILE: problem") for a missing or unreadable file, a format stb_image (or the
// PFM reader) cannot decode, a size over kMaxTexturePixels or over what memory allows, and a texel
// that is not finite or is negative.
Image read_texture_image(const std::filesystem::path& path, TexelEncoding encoding);
// The same from the file's bytes already in memory; `name` names it in messages, and its ending
// (.pfm) picks the PFM reader.
Image decode_texture_image(const std::string& bytes, const std::string& name, TexelEncoding encoding);

// 8-bit code c to its linear value: the sRGB curve (IEC 61966-2-1) or c / 255.
float decode_texel(std::uint8_t code, TexelEncoding encoding);

}  // namespace rt
