// Reading triangle meshes from Wavefront OBJ files through tinyobjloader. Positions, vertex
// normals, texture coordinates (u, v; a third w is ignored) and faces are used; materials and
// groups are ignored.
#pragma once

#include "common/triangle_mesh.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace rt {

// Polygons with more than three corners are split into a fan (c0, ck, ck+1).
// Throws InputError with one line "FILE:LINE: problem" (or "FILE: problem" where no single line
// is at fault) for: a missing or unreadable file, a vertex or normal that is not three finite
// numbers, a zero-length normal, a face with fewer than three corners, an index that is zero or
// out of range, and a file with no faces.
// Files over kMaxMeshFileBytes are refused before reading (1 GiB of text is some 10^7 triangles;
// the largest mesh shipped, 10^6 triangles, is 80 MB).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(1) << 30;
TriangleMesh load_obj(const std::filesystem::path& path);
// The same for the text of an OBJ file; `file` names it in the messages (the fuzz target's entry).
TriangleMesh parse_obj(const std::string& text, const std::string& file);

}  // namespace rt
