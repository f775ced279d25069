// Reading scene files. Every check names the file and the JSON path of what is wrong
// (common/json_node.h).
#include "common/error.h"
#include "common/file_io.h"
#include "common/json_node.h"
#include "common/obj_loader.h"
#include "common/scene.h"
#include "common/texture_image.h"

#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace rt {
namespace {

RenderSettings parse_render(const JsonNode& n) {
  n.expect_object({"width", "height", "spp", "seed", "max_depth", "pixel_center_only", "filter"});
  RenderSettings r;
  if (n.has("width")) r.width = int(n["width"].as_int(1, kMaxImageSide));
  if (n.has("height")) r.height = int(n["height"].as_int(1, kMaxImageSide));
  if (n.has("spp")) r.spp = int(n["spp"].as_int(1, kMaxSpp));
  if (n.has("seed")) r.seed = n["seed"].as_integer<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max());
  if (n.has("max_depth")) r.max_depth = int(n["max_depth"].as_int(0, 1000));
  if (n.has("pixel_center_only")) r.pixel_center_only = n["pixel_center_only"].as_bool();
  if (n.has("filter")) {
    const std::optional<PixelFilterType> filter = pixel_filter_from_name(n["filter"].as_string());
    if (!filter) n["filter"].fail("unknown filter (box, tent, gaussian, mitchell or blackman-harris)");
    r.filter = *filter;
  }
  return r;
}

CameraSpec parse_camera(const JsonNode& n) {
  n.expect_object({"position", "look_at", "up", "vfov", "aperture_radius", "focus_distance"});
  CameraSpec c;
  c.position = n["position"].as_position();
  c.look_at = n["look_at"].as_position();
  if (n.has("up")) c.up = n["up"].as_unit_vector();
  c.vfov_degrees = n["vfov"].as_float();
  if (!(c.vfov_degrees > 0.0f && c.vfov_degrees < 180.0f))
    n["vfov"].fail("vertical field of view must be in (0, 180) degrees");
  if (n.has("aperture_radius")) c.aperture_radius = n["aperture_radius"].as_float(0.0f, kMaxCoordinate, "aperture radius");
  if (n.has("focus_distance")) c.focus_distance = n["focus_distance"].as_size("focus distance");
  // In double: the camera's frame is built in float later, from these unit vectors.
  const glm::dvec3 view = glm::dvec3(c.look_at) - glm::dvec3(c.position);
  if (!(glm::length(view) > 0.0)) n["look_at"].fail("look_at equals position");
  if (!(glm::length(glm::cross(glm::normalize(view), glm::dvec3(c.up))) > 1e-6)) {
    if (!n.has("up")) n.fail("the default up (0, 1, 0) is parallel to the view direction; give 'up'");
    n["up"].fail("up must not be parallel to the view direction");
  }
  return c;
}

// Image files named by several materials (or by a material and the environment) are read once per
// encoding. Paths are relative to the scene file's folder.
class ImageCache {
 public:
  explicit ImageCache(std::filesystem::path folder) : folder_(std::move(folder)) {}
  std::shared_ptr<const Image> load(const JsonNode& file, TexelEncoding encoding, std::string& resolved) {
    resolved = (folder_ / file.as_string()).lexically_normal().string();
    std::shared_ptr<const Image>& image = images_[{resolved, encoding}];
    if (!image) {
      try {
        image = std::make_shared<const Image>(read_texture_image(resolved, encoding));
      } catch (const InputError& e) {
        file.fail(e.what());  // "scene.json: /materials/wood/albedo/file: wood.png: problem"
      }
    }
    return image;
  }

 private:
  std::filesystem::path folder_;
  std::map<std::pair<std::string, TexelEncoding>, std::shared_ptr<const Image>> images_;
};

// "albedo": {"file": "wood.png", "wrap": "repeat" | "clamp", "filter": "bilinear" | "nearest",
// "encoding": "srgb" | "linear"}: an image texture for a colour key (docs/scene-format.md).
// Its texels must lie in [0, hi], as the constant colour's channels must.
std::shared_ptr<const ImageTexture> parse_texture(const JsonNode& n, ImageCache& images, float hi, const char* what) {
  n.expect_object({"file", "wrap", "filter", "encoding"});
  ImageTexture texture;
  TexelEncoding encoding = TexelEncoding::srgb;
  if (n.has("encoding")) {
    const std::string e = n["encoding"].as_string();
    if (e != "srgb" && e != "linear") n["encoding"].fail("unknown encoding '" + e + "' (known: srgb, linear)");
    encoding = e == "srgb" ? TexelEncoding::srgb : TexelEncoding::linear;
  }
  if (n.has("wrap")) {
    const std::string w = n["wrap"].as_string();
    if (w != "repeat" && w != "clamp") n["wrap"].fail("unknown wrap mode '" + w + "' (known: repeat, clamp)");
    texture.wrap = w == "repeat" ? TextureWrap::repeat : TextureWrap::clamp;
  }
  if (n.has("filter")) {
    const std::string f = n["filter"].as_string();
    if (f != "bilinear" && f != "nearest") n["filter"].fail("unknown texture filter '" + f + "' (known: bilinear, nearest)");
    texture.filter = f == "bilinear" ? TextureFilter::bilinear : TextureFilter::nearest;
  }
  texture.texels = images.load(n["file"], encoding, texture.file);
  glm::dvec3 sum(0.0);
  for (const Color& c : texture.texels->pixels()) {
    sum += glm::dvec3(c);
    texture.largest = glm::max(texture.largest, c);
  }
  texture.mean = Color(sum / double(texture.texels->pixel_count()));
  if (max_component(texture.largest) > hi)
    n["file"].fail(texture.file + ": a texel is above " + std::to_string(int(hi)) + ", where " + what + " must be in [0, " +
                   std::to_string(int(hi)) + "]");
  return std::make_shared<const ImageTexture>(std::move(texture));
}

// A colour key that may instead name an image texture: sets the constant to the texture's mean.
void parse_color_or_texture(const JsonNode& n, ImageCache& images, const char* what, Color& constant,
                            std::shared_ptr<const ImageTexture>& texture) {
  if (n.value().is_object()) {
    texture = parse_texture(n, images, 1.0f, what);
    constant = texture->mean;
  } else {
    constant = n.as_color(1.0f, what);
  }
}

Checker parse_checker(const JsonNode& c) {
  c.expect_object({"albedo", "size"});
  return Checker{c["albedo"].as_color(1.0f, "albedo (more than 1 creates energy)"), c["size"].as_size("checker size")};
}

Material parse_material(const JsonNode& n, const std::string& name, ImageCache& images) {
  n.expect_object();
  Material m;
  m.name = name;
  const std::string type = n.has("type") ? n["type"].as_string() : "diffuse";
  if (type == "diffuse") {
    n.expect_object({"type", "albedo", "specular", "shininess", "emission", "checker"});
    if (n.has("albedo")) parse_color_or_texture(n["albedo"], images, "albedo (more than 1 creates energy)", m.albedo, m.albedo_texture);
    if (n.has("specular")) m.specular = n["specular"].as_color(1.0f, "specular reflectance");
    if (n.has("shininess")) m.shininess = n["shininess"].as_float(0.0f, 1e6f, "shininess");
    if (n.has("checker")) m.checker = parse_checker(n["checker"]);
  } else if (type == "mirror") {
    n.expect_object({"type", "reflectance", "emission"});
    m.type = MaterialType::mirror;
    if (n.has("reflectance")) m.reflectance = n["reflectance"].as_color(1.0f, "reflectance (more than 1 creates energy)");
  } else if (type == "dielectric") {
    n.expect_object({"type", "ior", "emission"});
    m.type = MaterialType::dielectric;
    if (n.has("ior")) m.ior = n["ior"].as_float(1.0f, 10.0f, "index of refraction");
  } else if (type == "phong") {
    n.expect_object({"type", "albedo", "specular", "shininess", "emission", "checker"});
    m.type = MaterialType::phong;
    m.specular = Color(0.2f);
    if (n.has("albedo")) parse_color_or_texture(n["albedo"], images, "albedo (more than 1 creates energy)", m.albedo, m.albedo_texture);
    if (n.has("specular")) parse_color_or_texture(n["specular"], images, "specular reflectance", m.specular, m.specular_texture);
    if (n.has("shininess")) m.shininess = n["shininess"].as_float(0.0f, 1e6f, "shininess");
    if (n.has("checker")) m.checker = parse_checker(n["checker"]);
    // Lambert reflects at most rho_d and the normalized lobe at most rho_s, so their sum must not
    // exceed 1 (Lafortune & Willems 1994), with either albedo of a checker and any texel of a
    // texture (the largest of each, a bound even where they are not at the same point).
    Color largest_albedo = m.checker ? glm::max(m.albedo, m.checker->albedo) : m.albedo;
    if (m.albedo_texture) largest_albedo = glm::max(largest_albedo, m.albedo_texture->largest);
    const Color largest_specular = m.specular_texture ? m.specular_texture->largest : m.specular;
    if (max_component(largest_albedo + largest_specular) > 1.0f)
      n.fail("albedo + specular exceeds 1 in some channel: the surface would reflect more than it receives");
  } else if (type == "microfacet") {
    n.expect_object({"type", "specular", "roughness", "emission"});
    m.type = MaterialType::microfacet;
    m.specular = Color(0.95f, 0.64f, 0.54f);  // copper's normal-incidence reflectance
    if (n.has("specular"))
      parse_color_or_texture(n["specular"], images, "normal-incidence reflectance F0", m.specular, m.specular_texture);
    if (n.has("roughness")) m.roughness = n["roughness"].as_float(0.001f, 1.0f, "roughness (GGX alpha)");
  } else {
    n["type"].fail("unknown material type '" + type +
                   "' (known: diffuse, mirror, dielectric, phong, microfacet)");
  }
  if (n.has("emission")) m.emission = n["emission"].as_color(3.0e38f, "emission");
  if (m.checker && m.albedo_texture) n["checker"].fail("a material has a checker or an albedo texture, not both");
  return m;
}

template <size_t N>
std::array<Vec2, N> parse_uvs(const JsonNode& n) {
  if (n.expect_array() != N) n.fail("expected " + std::to_string(N) + " texture coordinates, one per vertex");
  std::array<Vec2, N> uv;
  for (size_t i = 0; i < N; ++i) {
    const JsonNode c = n.at(i);
    if (c.expect_array() != 2) c.fail("expected an array of 2 numbers (u, v)");
    uv[i] = Vec2(c.at(0).as_float(-1e6f, 1e6f, "texture coordinate"), c.at(1).as_float(-1e6f, 1e6f, "texture coordinate"));
  }
  return uv;
}

template <size_t N>
std::array<Vec3, N> parse_vertices(const JsonNode& n) {
  if (n.expect_array() != N) n.fail("expected " + std::to_string(N) + " vertices");
  std::array<Vec3, N> v;
  for (size_t i = 0; i < N; ++i) v[i] = n.at(i).as_position();
  return v;
}

// "transform": {"scale": s or [sx, sy, sz], "rotate": [x, y, z] degrees, "translate": [x, y, z]},
// each optional.
Transform parse_transform(const JsonNode& n) {
  n.expect_object({"scale", "rotate", "translate"});
  Vec3 scale(1.0f), rotate(0.0f), translate(0.0f);
  if (n.has("scale")) {
    const JsonNode s = n["scale"];
    scale = s.value().is_array() ? s.as_vec3() : Vec3(s.as_float());
    if (!(scale.x != 0.0f && scale.y != 0.0f && scale.z != 0.0f))
      s.fail("scale must not be zero on any axis (the mesh would be flat)");
  }
  if (n.has("rotate")) rotate = n["rotate"].as_vec3();
  if (n.has("translate")) translate = n["translate"].as_position();
  return Transform::from_scale_rotate_translate(scale, rotate, translate);
}

// A round shape (sphere, torus, disk) reaches `reach` from its centre in every direction: its box
// must lie within +-kMaxCoordinate (scene.h).
void require_inside_limit(const JsonNode& n, Vec3 center, double reach) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(double(center[i])) + reach > double(kMaxCoordinate))
      n.fail("the shape reaches beyond +-1e18 (its centre plus its size), where squared distances overflow float");
}

// The largest |coordinate| of a mesh's vertices along each axis.
glm::dvec3 vertex_extent(const TriangleMesh& mesh) {
  glm::dvec3 extent(0.0);
  for (const Vec3& p : mesh.positions) extent = glm::max(extent, glm::abs(glm::dvec3(p)));
  return extent;
}

// A placed mesh's box: a bound on every coordinate of M p + t over the mesh's vertices p (whose
// largest coordinates are `extent`), with each term of the float sums the renderer computes
// bounded by it, so that none of them can overflow.
void require_placed_mesh_inside_limit(const JsonNode& n, glm::dvec3 extent, const Transform& transform) {
  for (int i = 0; i < 3; ++i) {
    double reach = std::abs(double(transform.matrix[3][i]));
    for (int j = 0; j < 3; ++j) reach += std::abs(double(transform.matrix[j][i])) * extent[j];
    if (!(reach <= double(kMaxCoordinate)))
      n.fail("the placed mesh reaches beyond +-1e18 (its vertices scaled, rotated and translated), where squared "
             "distances overflow float");
  }
}

// Meshes named by several shapes are read once.
class MeshCache {
 public:
  explicit MeshCache(std::filesystem::path folder) : folder_(std::move(folder)) {}
  Mesh load(const JsonNode& n) {
    const std::filesystem::path file = (folder_ / n["file"].as_string()).lexically_normal();
    Entry& entry = meshes_[file.string()];
    if (!entry.mesh) {
      try {
        entry.mesh = std::make_shared<const TriangleMesh>(load_obj(file));
      } catch (const InputError& e) {
        n["file"].fail(e.what());  // "scene.json: /shapes/3/file: mesh.obj:12: problem"
      }
      entry.extent = vertex_extent(*entry.mesh);
    }
    const Transform transform = n.has("transform") ? parse_transform(n["transform"]) : Transform{};
    require_placed_mesh_inside_limit(n, entry.extent, transform);
    return Mesh{file.string(), entry.mesh, transform};
  }

 private:
  struct Entry {
    std::shared_ptr<const TriangleMesh> mesh;
    glm::dvec3 extent{0.0};
  };
  std::filesystem::path folder_;
  std::map<std::string, Entry> meshes_;
};

Geometry parse_geometry(const JsonNode& n, const std::string& type, MeshCache& meshes) {
  if (type == "sphere") {
    n.expect_object({"type", "name", "material", "center", "radius"});
    const Sphere sphere{n["center"].as_position(), n["radius"].as_size("radius")};
    require_inside_limit(n, sphere.center, sphere.radius);
    return sphere;
  }
  if (type == "plane") {
    n.expect_object({"type", "name", "material", "point", "normal"});
    return Plane{n["point"].as_position(), n["normal"].as_unit_vector()};
  }
  if (type == "torus") {
    n.expect_object({"type", "name", "material", "center", "axis", "major_radius", "minor_radius"});
    Torus t{n["center"].as_position(), Vec3(0, 1, 0), n["major_radius"].as_size("major_radius"),
            n["minor_radius"].as_size("minor_radius")};
    if (n.has("axis")) t.axis = n["axis"].as_unit_vector();
    require_inside_limit(n, t.center, double(t.major_radius) + double(t.minor_radius));
    return t;
  }
  if (type == "triangle") {
    n.expect_object({"type", "name", "material", "vertices", "uvs"});
    Triangle triangle{parse_vertices<3>(n["vertices"])};
    if (n.has("uvs")) triangle.uvs = parse_uvs<3>(n["uvs"]);
    return triangle;
  }
  if (type == "quad") {
    n.expect_object({"type", "name", "material", "vertices", "uvs"});
    Quad quad{parse_vertices<4>(n["vertices"])};
    if (n.has("uvs")) quad.uvs = parse_uvs<4>(n["uvs"]);
    return quad;
  }
  if (type == "mesh") {
    n.expect_object({"type", "name", "material", "file", "transform"});
    return meshes.load(n);
  }
  if (type == "disk") {
    n.expect_object({"type", "name", "material", "center", "normal", "radius"});
    const Disk disk{n["center"].as_position(), n["normal"].as_unit_vector(), n["radius"].as_size("radius")};
    require_inside_limit(n, disk.center, disk.radius);
    return disk;
  }
  n["type"].fail("unknown shape type '" + type + "' (known: sphere, plane, torus, triangle, quad, mesh, disk)");
}

// "environment": {"radiance": [r, g, b]} (constant) or {"file": "sky.hdr", "scale": s, "rotation":
// degrees} (docs/scene-format.md).
Environment parse_environment(const JsonNode& n, ImageCache& images) {
  n.expect_object({"file", "radiance", "scale", "rotation"});
  Environment e;
  if (n.has("file") == n.has("radiance")) n.fail("give either 'file' (an image) or 'radiance' (a constant colour)");
  if (n.has("radiance")) {
    if (n.has("scale")) n["scale"].fail("'scale' multiplies an image; a constant environment gives its 'radiance'");
    e.scale = n["radiance"].as_color(1e30f, "environment radiance");
  } else {
    e.image = images.load(n["file"], TexelEncoding::srgb, e.file);
    if (n.has("scale")) e.scale = Color(n["scale"].as_float(0.0f, 1e30f, "environment scale"));
    float brightest = 0.0f;
    for (const Color& c : e.image->pixels()) brightest = std::max(brightest, max_component(c));
    if (!(brightest * max_component(e.scale) <= 1e30f))
      n.fail("the environment's radiance (texels times scale) exceeds 1e30");
  }
  if (n.has("rotation")) e.rotation_degrees = n["rotation"].as_float(-3600.0f, 3600.0f, "rotation (degrees about +y)");
  return e;
}

PointLight parse_light(const JsonNode& n) {
  n.expect_object({"type", "position", "intensity"});
  if (n["type"].as_string() != "point")
    n["type"].fail("unknown light type '" + n["type"].as_string() + "' (known: point)");
  return PointLight{n["position"].as_position(), n["intensity"].as_color(3.0e38f, "intensity")};
}

}  // namespace

SceneDescription parse_scene(const std::string& text, const std::string& source) {
  // nlohmann's parser takes a NUL byte for the end of the input and would accept whatever follows.
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    throw InputError(printable(source) + ": a NUL byte at offset " + std::to_string(nul) + ": not a JSON text file");
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::exception& e) {
    // A syntax error (with its byte position) or a number that overflows a double; keep
    // nlohmann's description, drop its "[json.exception...]" tag.
    std::string what = e.what();
    const size_t tag_end = what.find("] ");
    if (tag_end != std::string::npos) what = what.substr(tag_end + 2);
    throw InputError(printable(source + ": malformed JSON: " + what));
  }
  const JsonNode root(json, "", source);
  root.expect_object({"render", "camera", "background", "environment", "materials", "shapes", "lights"});

  SceneDescription scene;
  scene.source = source;
  if (root.has("render")) scene.render = parse_render(root["render"]);
  scene.camera = parse_camera(root["camera"]);
  if (root.has("background")) scene.background = root["background"].as_color(3.0e38f, "background radiance");
  const std::filesystem::path folder = std::filesystem::path(source).parent_path();
  ImageCache images(folder);
  if (root.has("environment")) {
    if (root.has("background"))
      root["environment"].fail("a scene has a background or an environment, not both (the environment is what escaping rays see)");
    scene.environment = parse_environment(root["environment"], images);
  }

  std::map<std::string, int> material_index;
  const JsonNode materials = root["materials"];
  materials.expect_object();  // any name; each material is checked below
  for (const auto& item : json["materials"].items()) {
    const JsonNode m(item.value(), "/materials/" + item.key(), scene.source);
    material_index[item.key()] = int(scene.materials.size());
    scene.materials.push_back(parse_material(m, item.key(), images));
  }

  MeshCache meshes(folder);
  const JsonNode shapes = root["shapes"];
  const size_t shape_count = shapes.expect_array();
  for (size_t i = 0; i < shape_count; ++i) {
    const JsonNode s = shapes.at(i);
    s.expect_object();
    Shape shape;
    shape.geometry = parse_geometry(s, s["type"].as_string(), meshes);
    if (s.has("name")) shape.name = s["name"].as_string();
    const std::string material = s["material"].as_string();
    const auto found = material_index.find(material);
    if (found == material_index.end()) s["material"].fail("unknown material '" + material + "'");
    shape.material = found->second;
    scene.shapes.push_back(std::move(shape));
  }

  if (root.has("lights")) {
    const JsonNode lights = root["lights"];
    const size_t light_count = lights.expect_array();
    for (size_t i = 0; i < light_count; ++i) scene.lights.push_back(parse_light(lights.at(i)));
  }
  return scene;
}

std::uint64_t triangle_count(const SceneDescription& scene) {
  std::uint64_t triangles = 0;
  for (const Shape& shape : scene.shapes) {
    if (const Mesh* mesh = std::get_if<Mesh>(&shape.geometry)) triangles += mesh->mesh->triangles.size();
    if (std::holds_alternative<Quad>(shape.geometry)) triangles += 2;
    if (std::holds_alternative<Triangle>(shape.geometry)) triangles += 1;
  }
  return triangles;
}

SceneDescription load_scene(const std::filesystem::path& path) {
  return parse_scene(read_input_file(path, "scene file", kMaxSceneFileBytes), path.string());
}

std::vector<std::string> files_read_by(const SceneDescription& scene) {
  std::vector<std::string> files;
  for (const Shape& shape : scene.shapes)
    if (const Mesh* mesh = std::get_if<Mesh>(&shape.geometry)) files.push_back(mesh->file);
  for (const Material& material : scene.materials)
    for (const auto& texture : {material.albedo_texture, material.specular_texture})
      if (texture) files.push_back(texture->file);
  if (scene.environment && !scene.environment->file.empty()) files.push_back(scene.environment->file);
  return files;
}

}  // namespace rt
