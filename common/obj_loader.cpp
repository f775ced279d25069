// tinyobjloader does the parsing, but it reads an unparsable number such as "nan" as 0 and reports
// out-of-range indices against the file's last line. So a first pass over the lines records where
// every vertex, normal and face statement is and checks the numbers, and every problem found
// afterwards can still name its line.
#include "common/obj_loader.h"

#include "common/error.h"
#include "common/file_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>

namespace rt {
namespace {

struct ObjLines {
  std::vector<int> face_lines;  // line number of each 'f' statement, in file order
  size_t vertex_count = 0;
  size_t normal_count = 0;
  size_t texture_count = 0;
};

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

// Reads the first `count` coordinates of a 'v', 'vn' or 'vt' statement; returns the offending word,
// if any. Read in double, so that a number too small for float (1e-50) becomes 0 as in any OBJ
// reader, while one too large for it (1e40), like nan and inf, is refused.
std::optional<std::string> read_numbers(const std::vector<std::string_view>& words, int count, Vec3& out) {
  if (words.size() < size_t(count) + 1) return std::string("(missing)");
  for (int i = 0; i < count; ++i) {
    const std::string word(words[size_t(i) + 1]);
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size() || !(std::abs(value) <= double(std::numeric_limits<float>::max())))
      return word;
    out[i] = float(value);
  }
  return std::nullopt;
}

// Where one kind of index (vertex, texture, normal) may point, and the positive indices that point
// past the statements read so far, checked against the file's total once it is known.
struct IndexKind {
  const char* name;    // "vertex", "texture", "normal"
  const char* plural;  // "vertices", "texture coordinates", "normals"
  size_t& count;       // statements of this kind so far
  struct Forward {
    int line;
    std::string text;
    long long value;
  };
  std::vector<Forward> forward;
};

// One corner field, as written. Returns false when it is not a non-zero integer (the caller names
// the corner). OBJ counts from 1; a negative index counts back from the last statement before the
// face. Throws for an index that points before the first statement, quoting it exactly; keeps in
// kind.forward a positive index past the statements so far.
bool check_index(std::string_view field, IndexKind& kind, int line, const std::string& at) {
  long long index = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), index);
  if (field.empty() || end != field.data() + field.size() || error == std::errc::invalid_argument) return false;
  const bool overflow = error == std::errc::result_out_of_range;
  const std::string text(field);
  if (overflow ? field[0] == '-' : index < -(long long)kind.count)
    throw InputError(at + kind.name + " index " + text + " is out of range (" + std::to_string(kind.count) + " " +
                     kind.plural + " come before it)");
  if (overflow) index = std::numeric_limits<long long>::max();  // past any file's statements
  if (index == 0) return false;
  if (index > (long long)kind.count) kind.forward.push_back({line, text, index});
  return true;
}

// A face corner "v", "v/vt", "v/vt/vn" or "v//vn": each present index a non-zero integer in range.
void check_corner(std::string_view corner, IndexKind* kinds[3], int line, const std::string& at) {
  const std::string corner_text(corner);
  bool well_formed = true;
  for (int fields = 0; well_formed; ++fields) {
    const size_t slash = corner.find('/');
    const std::string_view field = corner.substr(0, slash);
    if (fields == 3) well_formed = false;
    else if (!(field.empty() && fields == 1)) well_formed = check_index(field, *kinds[fields], line, at);  // vt may be left out
    if (slash == std::string_view::npos) break;
    corner.remove_prefix(slash + 1);
  }
  if (!well_formed)
    throw InputError(at + "face corner '" + corner_text + "' is not v, v/vt, v/vt/vn or v//vn with non-zero " +
                     "indices (OBJ counts from 1, negative indices count back)");
}

ObjLines scan_lines(const std::string& text, const std::string& file) {
  ObjLines lines;
  IndexKind vertices{"vertex", "vertices", lines.vertex_count, {}},
      textures{"texture", "texture coordinates", lines.texture_count, {}},
      normals{"normal", "normals", lines.normal_count, {}};
  IndexKind* kinds[3] = {&vertices, &textures, &normals};
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::vector<std::string_view> words = split_words(line);
    if (words.empty()) continue;
    const std::string at = file + ":" + std::to_string(number) + ": ";
    auto fail = [&](const std::string& problem) { throw InputError(at + problem); };
    Vec3 v;
    if (words[0] == "v") {
      if (const auto bad = read_numbers(words, 3, v))
        fail("vertex needs three finite coordinates, got '" + *bad + "'");
      ++lines.vertex_count;
    } else if (words[0] == "vn") {
      if (const auto bad = read_numbers(words, 3, v))
        fail("normal needs three finite coordinates, got '" + *bad + "'");
      if (!(glm::length(glm::dvec3(v)) > 0.0)) fail("normal has zero length");
      ++lines.normal_count;
    } else if (words[0] == "vt") {
      if (const auto bad = read_numbers(words, 2, v))
        fail("texture coordinate needs two finite numbers, got '" + *bad + "'");
      ++lines.texture_count;
    } else if (words[0] == "f") {
      if (words.size() < 4) fail("a face needs at least three corners");
      for (size_t k = 1; k < words.size(); ++k) check_corner(words[k], kinds, number, at);
      lines.face_lines.push_back(number);
    }
  }
  // Positive indices may point forward; by the end of the file they must point at something.
  for (const IndexKind* kind : kinds)
    for (const IndexKind::Forward& f : kind->forward)
      if (f.value > (long long)kind->count)
        throw InputError(file + ":" + std::to_string(f.line) + ": " + kind->name + " index " + f.text +
                         " is out of range (the file has " + std::to_string(kind->count) + " " + kind->plural + ")");
  return lines;
}

}  // namespace

TriangleMesh load_obj(const std::filesystem::path& path) {
  return parse_obj(read_input_file(path, "mesh file", kMaxMeshFileBytes), path.string());
}

TriangleMesh parse_obj(const std::string& text, const std::string& file) {
  const ObjLines lines = scan_lines(text, file);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // fans below, so each face keeps its line number
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    std::string error = reader.Error();
    while (!error.empty() && (error.back() == '\n' || error.back() == '.')) error.pop_back();
    throw InputError(file + ": " + (error.empty() ? "not a valid OBJ file" : error.substr(0, error.find('\n'))));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  if (attrib.vertices.size() != 3 * lines.vertex_count || attrib.normals.size() != 3 * lines.normal_count ||
      attrib.texcoords.size() != 2 * lines.texture_count)
    throw InputError(file + ": vertex, normal or texture statements could not be read");

  TriangleMesh mesh;
  for (size_t i = 0; i < lines.vertex_count; ++i)
    mesh.positions.emplace_back(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
  for (size_t i = 0; i < lines.normal_count; ++i)
    mesh.normals.push_back(glm::normalize(
        Vec3(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2])));
  for (size_t i = 0; i < lines.texture_count; ++i) mesh.uvs.emplace_back(attrib.texcoords[2 * i], attrib.texcoords[2 * i + 1]);

  size_t face = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t corner = 0;
    for (const unsigned int corner_count : shape.mesh.num_face_vertices) {
      if (face >= lines.face_lines.size()) throw InputError(file + ": face statements could not be read");
      const std::string at = file + ":" + std::to_string(lines.face_lines[face]) + ": ";
      std::vector<std::uint32_t> positions;
      std::vector<std::int32_t> normals, uvs;
      for (unsigned int k = 0; k < corner_count; ++k, ++corner) {
        const tinyobj::index_t index = shape.mesh.indices[corner];
        if (index.vertex_index < 0 || size_t(index.vertex_index) >= lines.vertex_count)
          throw InputError(at + "vertex index " + std::to_string(index.vertex_index + 1) +
                           " is out of range (the file has " + std::to_string(lines.vertex_count) + " vertices)");
        if (index.normal_index >= 0 && size_t(index.normal_index) >= lines.normal_count)
          throw InputError(at + "normal index " + std::to_string(index.normal_index + 1) +
                           " is out of range (the file has " + std::to_string(lines.normal_count) + " normals)");
        if (index.texcoord_index >= 0 && size_t(index.texcoord_index) >= lines.texture_count)
          throw InputError(at + "texture index " + std::to_string(index.texcoord_index + 1) +
                           " is out of range (the file has " + std::to_string(lines.texture_count) +
                           " texture coordinates)");
        positions.push_back(std::uint32_t(index.vertex_index));
        normals.push_back(index.normal_index);
        uvs.push_back(index.texcoord_index);
      }
      auto all_given = [](const std::vector<std::int32_t>& indices) {
        return std::all_of(indices.begin(), indices.end(), [](std::int32_t i) { return i >= 0; });
      };
      const bool all_normals = all_given(normals), all_uvs = all_given(uvs);
      for (size_t k = 1; k + 1 < positions.size(); ++k) {
        mesh.triangles.push_back({positions[0], positions[k], positions[k + 1]});
        if (all_normals) mesh.triangle_normals.push_back({normals[0], normals[k], normals[k + 1]});
        else mesh.triangle_normals.push_back({-1, -1, -1});
        if (all_uvs) mesh.triangle_uvs.push_back({uvs[0], uvs[k], uvs[k + 1]});
        else mesh.triangle_uvs.push_back({-1, -1, -1});
      }
      ++face;
    }
  }
  if (face != lines.face_lines.size()) throw InputError(file + ": face statements could not be read");
  if (mesh.triangles.empty()) throw InputError(file + ": the mesh has no faces");
  if (mesh.normals.empty()) mesh.triangle_normals.clear();
  if (mesh.uvs.empty()) mesh.triangle_uvs.clear();
  return mesh;
}

}  // namespace rt
