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

// Reads the three coordinates of a 'v' or 'vn' statement; returns the offending word, if any.
std::optional<std::string> read_three_numbers(const std::vector<std::string_view>& words, Vec3& out) {
  if (words.size() < 4) return std::string("(missing)");
  for (int i = 0; i < 3; ++i) {
    const std::string_view word = words[size_t(i) + 1];
    float value = 0.0f;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value))
      return std::string(word);
    out[i] = value;
  }
  return std::nullopt;
}

// A face corner "v", "v/vt", "v/vt/vn" or "v//vn": each present index a non-zero integer.
bool valid_corner(std::string_view corner) {
  int fields = 0;
  while (true) {
    const size_t slash = corner.find('/');
    const std::string_view field = corner.substr(0, slash);
    ++fields;
    if (!(field.empty() && fields == 2)) {  // only the texture index may be left out
      long long index = 0;
      const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), index);
      if (error != std::errc() || end != field.data() + field.size() || index == 0) return false;
    }
    if (slash == std::string_view::npos) return fields <= 3;
    corner.remove_prefix(slash + 1);
  }
}

ObjLines scan_lines(const std::string& text, const std::string& file) {
  ObjLines lines;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::vector<std::string_view> words = split_words(line);
    if (words.empty()) continue;
    auto fail = [&](const std::string& problem) {
      throw InputError(file + ":" + std::to_string(number) + ": " + problem);
    };
    Vec3 v;
    if (words[0] == "v") {
      if (const auto bad = read_three_numbers(words, v))
        fail("vertex needs three finite coordinates, got '" + *bad + "'");
      ++lines.vertex_count;
    } else if (words[0] == "vn") {
      if (const auto bad = read_three_numbers(words, v))
        fail("normal needs three finite coordinates, got '" + *bad + "'");
      if (!(glm::length(v) > 0.0f)) fail("normal has zero length");
      ++lines.normal_count;
    } else if (words[0] == "f") {
      if (words.size() < 4) fail("a face needs at least three corners");
      for (size_t k = 1; k < words.size(); ++k)
        if (!valid_corner(words[k]))
          fail("face corner '" + std::string(words[k]) + "' is not v, v/vt, v/vt/vn or v//vn with non-zero " +
               "indices (OBJ counts from 1, negative indices count back)");
      lines.face_lines.push_back(number);
    }
  }
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
  if (attrib.vertices.size() != 3 * lines.vertex_count || attrib.normals.size() != 3 * lines.normal_count)
    throw InputError(file + ": vertex or normal statements could not be read");

  TriangleMesh mesh;
  for (size_t i = 0; i < lines.vertex_count; ++i)
    mesh.positions.emplace_back(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
  for (size_t i = 0; i < lines.normal_count; ++i)
    mesh.normals.push_back(glm::normalize(
        Vec3(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2])));

  size_t face = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t corner = 0;
    for (const unsigned int corner_count : shape.mesh.num_face_vertices) {
      if (face >= lines.face_lines.size()) throw InputError(file + ": face statements could not be read");
      const std::string at = file + ":" + std::to_string(lines.face_lines[face]) + ": ";
      std::vector<std::uint32_t> positions;
      std::vector<std::int32_t> normals;
      for (unsigned int k = 0; k < corner_count; ++k, ++corner) {
        const tinyobj::index_t index = shape.mesh.indices[corner];
        if (index.vertex_index < 0 || size_t(index.vertex_index) >= lines.vertex_count)
          throw InputError(at + "vertex index " + std::to_string(index.vertex_index + 1) +
                           " is out of range (the file has " + std::to_string(lines.vertex_count) + " vertices)");
        if (index.normal_index >= 0 && size_t(index.normal_index) >= lines.normal_count)
          throw InputError(at + "normal index " + std::to_string(index.normal_index + 1) +
                           " is out of range (the file has " + std::to_string(lines.normal_count) + " normals)");
        positions.push_back(std::uint32_t(index.vertex_index));
        normals.push_back(index.normal_index);
      }
      const bool all_normals = std::all_of(normals.begin(), normals.end(), [](std::int32_t n) { return n >= 0; });
      for (size_t k = 1; k + 1 < positions.size(); ++k) {
        mesh.triangles.push_back({positions[0], positions[k], positions[k + 1]});
        if (all_normals) mesh.triangle_normals.push_back({normals[0], normals[k], normals[k + 1]});
        else mesh.triangle_normals.push_back({-1, -1, -1});
      }
      ++face;
    }
  }
  if (face != lines.face_lines.size()) throw InputError(file + ": face statements could not be read");
  if (mesh.triangles.empty()) throw InputError(file + ": the mesh has no faces");
  if (mesh.normals.empty()) mesh.triangle_normals.clear();
  return mesh;
}

}  // namespace rt
