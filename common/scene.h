// A scene as its JSON file describes it: plain data, no intersection code. Each stage turns this
// description into what it can render (stage 1: spheres, planes, tori; stage 2 adds triangles).
// The file format, with every default, is documented in docs/scene-format.md.
#pragma once

#include "common/camera.h"
#include "common/image.h"
#include "common/math.h"
#include "common/transform.h"
#include "common/triangle_mesh.h"

#include <glm/common.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace rt {

// The pixel reconstruction filters of stage 1 (01-ray-casting/pixel_filter.h has their shapes).
enum class PixelFilterType { box, tent, gaussian, mitchell, blackman_harris };
inline constexpr std::array<std::pair<PixelFilterType, const char*>, 5> kPixelFilterNames{{
    {PixelFilterType::box, "box"},
    {PixelFilterType::tent, "tent"},
    {PixelFilterType::gaussian, "gaussian"},
    {PixelFilterType::mitchell, "mitchell"},
    {PixelFilterType::blackman_harris, "blackman-harris"},
}};
inline const char* pixel_filter_name(PixelFilterType type) {
  for (const auto& [t, name] : kPixelFilterNames)
    if (t == type) return name;
  return "?";
}
inline std::optional<PixelFilterType> pixel_filter_from_name(const std::string& name) {
  for (const auto& [type, known] : kPixelFilterNames)
    if (name == known) return type;
  return std::nullopt;
}

// What the command line may override (common/cli.h); the scene file gives the defaults.
struct RenderSettings {
  int width = 512;
  int height = 512;
  int spp = 16;
  std::uint64_t seed = 0;
  int max_depth = 5;               // recursion / path depth limit for the later stages
  bool pixel_center_only = false;  // one ray through each pixel centre instead of area samples
  PixelFilterType filter = PixelFilterType::box;  // how samples spread over and around a pixel

  // Scale-out (docs/scale-out.md): a run takes samples [first_sample, first_sample + spp) of each
  // pixel, so batches rendered apart add up to one render; and only the pixels of `crop` when set.
  int first_sample = 0;
  std::optional<PixelRect> crop;

  // The pixels this run renders: the crop window, or the whole image.
  PixelRect window() const { return crop ? *crop : PixelRect{0, 0, width, height}; }
};

// A solid 3D checkerboard: cubes of side `size`, centred on the origin, alternate between the
// material's albedo and this one. Centred cells keep a plane through a multiple of `size` inside
// one layer of cubes, so rounding in the hit point cannot flip its colour.
struct Checker {
  Color albedo;
  float size;
};

// An image texture as a scene file names it (docs/scene-format.md): its texels, already linear
// (common/texture_image.h), and how stage 4 looks them up (04-radiometry/texture.h). Texture
// coordinates (u, v) run right and UP: (0, 0) is the image's bottom-left corner, (1, 1) its
// top-right; `repeat` tiles the plane with the image, `clamp` extends its edge texels.
enum class TextureWrap { repeat, clamp };
enum class TextureFilter { nearest, bilinear };
struct ImageTexture {
  std::string file;  // as resolved from the scene file, for messages
  std::shared_ptr<const Image> texels;  // shared by the materials that name the same file
  TextureWrap wrap = TextureWrap::repeat;
  TextureFilter filter = TextureFilter::bilinear;
  Color mean{0.0f};     // the texels' average: what stages 1-3 shade with, which look no texture up
  Color largest{0.0f};  // the largest texel value per channel, for the loader's energy checks
};

enum class MaterialType {
  diffuse,     // Lambert + Blinn-Phong, shaded from the lights (stage 1 on)
  mirror,      // perfect specular reflection (stage 2 on)
  dielectric,  // glass: Fresnel-weighted reflection and refraction (stage 2 on)
  phong,       // Lambert plus an energy-conserving (normalized) Phong lobe (stage 4 on)
  microfacet,  // GGX microfacet reflection with Smith masking, a rough metal (stage 4 on)
};

struct Material {
  std::string name;
  MaterialType type = MaterialType::diffuse;
  Color albedo{0.8f};      // diffuse reflectance rho in [0, 1] per channel
  Color specular{0.0f};    // diffuse: Blinn-Phong specular; phong: lobe albedo; microfacet: F0
  float shininess = 32.0f; // diffuse: Blinn-Phong exponent; phong: the lobe's exponent
  float roughness = 0.2f;  // microfacet: GGX alpha in [0.001, 1]
  Color emission{0.0f};    // emitted radiance Le, from the front face only
  std::optional<Checker> checker;
  // Image textures in place of `albedo` and `specular` (stage 4 on). Each constant above then
  // holds its texture's mean, which stages 1-3, blind to textures, shade with.
  std::shared_ptr<const ImageTexture> albedo_texture, specular_texture;
  Color reflectance{1.0f}; // mirror: fraction reflected per channel
  float ior = 1.5f;        // dielectric: index of refraction inside (outside is 1, vacuum/air)

  // The diffuse reflectance at a surface point: the albedo, or the checker's colour there.
  Color albedo_at(Vec3 p) const {
    if (!checker) return albedo;
    const Vec3 cell = glm::floor(p / checker->size + 0.5f);
    // Parity per axis through fmod, which (unlike a cast to an integer) is defined for any float.
    auto odd_cell = [](float c) { return std::fmod(std::abs(c), 2.0f) >= 1.0f; };
    const bool odd = odd_cell(cell.x) != (odd_cell(cell.y) != odd_cell(cell.z));
    return odd ? checker->albedo : albedo;
  }
};

struct Sphere {
  Vec3 center;
  float radius;
};
struct Plane {
  Vec3 point;
  Vec3 normal;  // unit length; the plane is two-sided
};
struct Torus {
  Vec3 center;
  Vec3 axis;  // unit length; the ring lies in the plane through center perpendicular to axis
  float major_radius;
  float minor_radius;
};
struct Triangle {
  std::array<Vec3, 3> vertices;  // outward normal (v1 - v0) x (v2 - v0)
  std::array<Vec2, 3> uvs{Vec2(0.0f, 0.0f), Vec2(1.0f, 0.0f), Vec2(0.0f, 1.0f)};  // texture coordinates
};
// Four corners in order. Meshed as (v0, v1, v2) + (v0, v2, v3), which is exact for planar
// parallelograms and DEFINES the surface otherwise (the Cornell box's red wall is not planar).
struct Quad {
  std::array<Vec3, 4> vertices;
  // Texture coordinates of the corners: by default the unit square, so an image covers the quad.
  std::array<Vec2, 4> uvs{Vec2(0.0f, 0.0f), Vec2(1.0f, 0.0f), Vec2(1.0f, 1.0f), Vec2(0.0f, 1.0f)};
};

// A triangle mesh from an OBJ file, placed in the world by `transform`. The mesh is shared, not
// copied, when the description is.
struct Mesh {
  std::string file;  // as resolved from the scene file, for messages
  std::shared_ptr<const TriangleMesh> mesh;  // in the OBJ file's own coordinates
  Transform transform;
};

// A flat disk, one-sided as an emitter: it emits towards `normal` (stage 4 on).
struct Disk {
  Vec3 center;
  Vec3 normal;  // unit length
  float radius;
};

using Geometry = std::variant<Sphere, Plane, Torus, Triangle, Quad, Mesh, Disk>;

// One shape of a scene as a renderer stores it: its geometry (in the form the renderer tests it),
// its material and its place in the scene file (for messages, debug views and the emitters).
template <class G>
struct Placed {
  G geometry;
  int material = 0;  // index into SceneDescription::materials
  int shape = -1;    // index into SceneDescription::shapes
};

struct Shape {
  std::string name;  // optional, for messages
  Geometry geometry;
  int material = 0;  // index into SceneDescription::materials
};

struct PointLight {
  Vec3 position;
  Color intensity;  // radiant intensity I, W/sr per channel
};

// Light from infinitely far away, arriving from every direction (stage 4's environment emitter):
// a latitude-longitude image (04-radiometry/environment_light.h has its mapping) times `scale`, or
// the constant radiance `scale` when there is no image. Turned by `rotation_degrees` about +y.
struct Environment {
  std::string file;                     // empty for a constant environment
  std::shared_ptr<const Image> image;   // linear radiance, row 0 at the top (straight up)
  Color scale{1.0f};
  float rotation_degrees = 0.0f;
};

struct SceneDescription {
  std::string source;  // the file it came from, for messages
  RenderSettings render;
  CameraSpec camera;
  Color background{0.0f};  // radiance of rays that escape (no scene has both it and an environment)
  std::optional<Environment> environment;
  std::vector<Material> materials;
  std::vector<Shape> shapes;
  std::vector<PointLight> lights;
};

// Throws InputError("FILE: /json/path: problem") for a missing or unreadable file, malformed JSON,
// a missing field, a wrong type, an unknown key, an unknown material, or a bad or non-finite number.
// Mesh files are read too, relative to the scene file's folder; their errors name the OBJ file and
// line (common/obj_loader.h).
SceneDescription load_scene(const std::filesystem::path& path);
// A scene file is a page of JSON; anything over 64 MiB is not one.
inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t(64) << 20;
// The same from text already in memory; `source` names it in messages.
SceneDescription parse_scene(const std::string& text, const std::string& source);
// Every file a scene read besides its own: meshes, textures and the environment map. No output may
// be one of them.
std::vector<std::string> files_read_by(const SceneDescription& scene);

// Every position a scene gives (vertices, centres, the camera, lights) and every bounded shape's
// box lie within +-kMaxCoordinate, and sizes are at most that: the squared distances every
// intersection test forms, the areas emitters are chosen by and the box areas the BVH's costs use
// then stay finite in float ((2e18)^2 = 4e36 < 3.4e38). The loader refuses anything beyond.
inline constexpr float kMaxCoordinate = 1e18f;

// The triangles a scene places in the world: a mesh's once for every shape that places it, a
// quad's two, a triangle's one (what the later stages build and store per triangle).
std::uint64_t triangle_count(const SceneDescription& scene);

// Largest image side and spp accepted from a scene or the command line. The side is only a bound
// against overflow; whether this machine can hold the image is checked against its memory before
// anything is allocated (check_image_fits in common/cli.h).
inline constexpr int kMaxImageSide = 1 << 20;
inline constexpr int kMaxSpp = 1 << 20;

}  // namespace rt
