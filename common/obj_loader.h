// Reading triangle meshes from Wavefront OBJ files through tinyobjloader. Positions, vertex
// normals and faces are used; texture coordinates, materials and groups are ignored.
#pragma once

#include "common/triangle_mesh.h"

#include <filesystem>

namespace rt {

// Polygons with more than three corners are split into a fan (c0, ck, ck+1).
// Throws InputError with one line "FILE:LINE: problem" (or "FILE: problem" where no single line
// is at fault) for: a missing or unreadable file, a vertex or normal that is not three finite
// numbers, a zero-length normal, a face with fewer than three corners, an index that is zero or
// out of range, and a file with no faces.
TriangleMesh load_obj(const std::filesystem::path& path);

}  // namespace rt
