// Reading scene files. Every check names the file and the JSON path (RFC 6901 pointer) of what is
// wrong, because a student's first scene will have a typo in it.
#include "common/error.h"
#include "common/file_io.h"
#include "common/obj_loader.h"
#include "common/scene.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace rt {
namespace {

using Json = nlohmann::json;

// A JSON value together with where it is, so every error can say so.
class Node {
 public:
  Node(const Json& value, std::string path, const std::string& source)
      : value_(value), path_(std::move(path)), source_(source) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(source_ + ": " + (path_.empty() ? "/" : path_) + ": " + problem);
  }

  const Json& value() const { return value_; }
  bool has(const char* key) const { return value_.contains(key); }

  Node operator[](const char* key) const {
    if (!value_.contains(key)) fail(std::string("missing field '") + key + "'");
    return Node(value_.at(key), path_ + "/" + key, source_);
  }
  Node at(size_t i) const {
    return Node(value_.at(i), path_ + "/" + std::to_string(i), source_);
  }

  // Objects may only hold the keys the format defines: a misspelt key is an error, not a
  // silently ignored default.
  void expect_object() const {
    if (!value_.is_object()) fail("expected an object, got " + type_name());
  }
  void expect_object(std::initializer_list<const char*> allowed) const {
    expect_object();
    const std::set<std::string> known(allowed.begin(), allowed.end());
    for (const auto& item : value_.items())
      if (!known.contains(item.key())) fail("unknown key '" + item.key() + "'");
  }

  size_t expect_array() const {
    if (!value_.is_array()) fail("expected an array, got " + type_name());
    return value_.size();
  }

  std::string as_string() const {
    if (!value_.is_string()) fail("expected a string, got " + type_name());
    return value_.get<std::string>();
  }

  float as_float() const {
    if (!value_.is_number()) fail("expected a number, got " + type_name());
    const double v = value_.get<double>();
    if (!std::isfinite(v) || std::abs(v) > 3.0e38) fail("number is not finite in float");
    return float(v);
  }

  float as_float(float lo, float hi, const char* what) const {
    const float v = as_float();
    if (!(v >= lo && v <= hi)) fail(std::string(what) + " must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + fmt(v));
    return v;
  }

  float as_positive(const char* what) const {
    const float v = as_float();
    if (!(v > 0.0f)) fail(std::string(what) + " must be positive, got " + fmt(v));
    return v;
  }

  long long as_int(long long lo, long long hi) const {
    if (!value_.is_number_integer()) fail("expected an integer, got " + type_name());
    const long long v = value_.get<long long>();
    if (v < lo || v > hi)
      fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
    return v;
  }

  bool as_bool() const {
    if (!value_.is_boolean()) fail("expected true or false, got " + type_name());
    return value_.get<bool>();
  }

  Vec3 as_vec3() const {
    if (!value_.is_array() || value_.size() != 3) fail("expected an array of 3 numbers");
    return Vec3(at(0).as_float(), at(1).as_float(), at(2).as_float());
  }

  Vec3 as_unit_vector() const {
    const Vec3 v = as_vec3();
    if (!(glm::length(v) > 0.0f)) fail("direction must not be zero");
    return glm::normalize(v);
  }

  Color as_color(float hi, const char* what) const {
    const Vec3 c = as_vec3();
    for (int i = 0; i < 3; ++i)
      if (!(c[i] >= 0.0f && c[i] <= hi))
        at(size_t(i)).fail(std::string(what) + " must be in [0, " + fmt(hi) + "], got " + fmt(c[i]));
    return c;
  }

 private:
  std::string type_name() const { return value_.type_name(); }
  static std::string fmt(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  const Json& value_;
  std::string path_;
  const std::string& source_;
};

RenderSettings parse_render(const Node& n) {
  n.expect_object({"width", "height", "spp", "seed", "max_depth", "pixel_center_only"});
  RenderSettings r;
  if (n.has("width")) r.width = int(n["width"].as_int(1, kMaxImageSide));
  if (n.has("height")) r.height = int(n["height"].as_int(1, kMaxImageSide));
  if (n.has("spp")) r.spp = int(n["spp"].as_int(1, kMaxSpp));
  if (n.has("seed")) r.seed = std::uint64_t(n["seed"].as_int(0, std::numeric_limits<long long>::max()));
  if (n.has("max_depth")) r.max_depth = int(n["max_depth"].as_int(0, 1000));
  if (n.has("pixel_center_only")) r.pixel_center_only = n["pixel_center_only"].as_bool();
  return r;
}

CameraSpec parse_camera(const Node& n) {
  n.expect_object({"position", "look_at", "up", "vfov"});
  CameraSpec c;
  c.position = n["position"].as_vec3();
  c.look_at = n["look_at"].as_vec3();
  if (n.has("up")) c.up = n["up"].as_vec3();
  c.vfov_degrees = n["vfov"].as_float();
  if (!(c.vfov_degrees > 0.0f && c.vfov_degrees < 180.0f))
    n["vfov"].fail("vertical field of view must be in (0, 180) degrees");
  if (!(glm::length(c.look_at - c.position) > 0.0f)) n["look_at"].fail("look_at equals position");
  const Vec3 forward = glm::normalize(c.look_at - c.position);
  if (!(glm::length(glm::cross(forward, c.up)) > 1e-6f * glm::length(c.up))) {
    if (!n.has("up")) n.fail("the default up (0, 1, 0) is parallel to the view direction; give 'up'");
    n["up"].fail("up must not be zero or parallel to the view direction");
  }
  return c;
}

Material parse_material(const Node& n, const std::string& name) {
  n.expect_object();
  Material m;
  m.name = name;
  const std::string type = n.has("type") ? n["type"].as_string() : "diffuse";
  if (type == "diffuse") {
    n.expect_object({"type", "albedo", "specular", "shininess", "emission", "checker"});
    if (n.has("albedo")) m.albedo = n["albedo"].as_color(1.0f, "albedo (more than 1 creates energy)");
    if (n.has("specular")) m.specular = n["specular"].as_color(1.0f, "specular reflectance");
    if (n.has("shininess")) m.shininess = n["shininess"].as_float(0.0f, 1e6f, "shininess");
    if (n.has("checker")) {
      const Node c = n["checker"];
      c.expect_object({"albedo", "size"});
      m.checker = Checker{c["albedo"].as_color(1.0f, "albedo (more than 1 creates energy)"),
                          c["size"].as_positive("checker size")};
    }
  } else if (type == "mirror") {
    n.expect_object({"type", "reflectance", "emission"});
    m.type = MaterialType::mirror;
    if (n.has("reflectance")) m.reflectance = n["reflectance"].as_color(1.0f, "reflectance (more than 1 creates energy)");
  } else if (type == "dielectric") {
    n.expect_object({"type", "ior", "emission"});
    m.type = MaterialType::dielectric;
    if (n.has("ior")) m.ior = n["ior"].as_float(1.0f, 10.0f, "index of refraction");
  } else if (type == "phong") {
    n.expect_object({"type", "albedo", "specular", "shininess", "emission"});
    m.type = MaterialType::phong;
    m.specular = Color(0.2f);
    if (n.has("albedo")) m.albedo = n["albedo"].as_color(1.0f, "albedo (more than 1 creates energy)");
    if (n.has("specular")) m.specular = n["specular"].as_color(1.0f, "specular reflectance");
    if (n.has("shininess")) m.shininess = n["shininess"].as_float(0.0f, 1e6f, "shininess");
    // Lambert reflects at most rho_d and the normalized lobe at most rho_s, so their sum must not
    // exceed 1 (Lafortune & Willems 1994).
    if (max_component(m.albedo + m.specular) > 1.0f)
      n.fail("albedo + specular exceeds 1 in some channel: the surface would reflect more than it receives");
  } else if (type == "microfacet") {
    n.expect_object({"type", "specular", "roughness", "emission"});
    m.type = MaterialType::microfacet;
    m.specular = Color(0.95f, 0.64f, 0.54f);  // copper's normal-incidence reflectance
    if (n.has("specular")) m.specular = n["specular"].as_color(1.0f, "normal-incidence reflectance F0");
    if (n.has("roughness")) m.roughness = n["roughness"].as_float(0.001f, 1.0f, "roughness (GGX alpha)");
  } else {
    n["type"].fail("unknown material type '" + type +
                   "' (known: diffuse, mirror, dielectric, phong, microfacet)");
  }
  if (n.has("emission")) m.emission = n["emission"].as_color(3.0e38f, "emission");
  return m;
}

template <size_t N>
std::array<Vec3, N> parse_vertices(const Node& n) {
  if (n.expect_array() != N) n.fail("expected " + std::to_string(N) + " vertices");
  std::array<Vec3, N> v;
  for (size_t i = 0; i < N; ++i) v[i] = n.at(i).as_vec3();
  return v;
}

// "transform": {"scale": s or [sx, sy, sz], "rotate": [x, y, z] degrees, "translate": [x, y, z]},
// each optional.
Transform parse_transform(const Node& n) {
  n.expect_object({"scale", "rotate", "translate"});
  Vec3 scale(1.0f), rotate(0.0f), translate(0.0f);
  if (n.has("scale")) {
    const Node s = n["scale"];
    scale = s.value().is_array() ? s.as_vec3() : Vec3(s.as_float());
    if (!(scale.x != 0.0f && scale.y != 0.0f && scale.z != 0.0f))
      s.fail("scale must not be zero on any axis (the mesh would be flat)");
  }
  if (n.has("rotate")) rotate = n["rotate"].as_vec3();
  if (n.has("translate")) translate = n["translate"].as_vec3();
  return Transform::from_scale_rotate_translate(scale, rotate, translate);
}

// Meshes named by several shapes are read once.
class MeshCache {
 public:
  explicit MeshCache(std::filesystem::path folder) : folder_(std::move(folder)) {}
  Mesh load(const Node& n) {
    const std::filesystem::path file = (folder_ / n["file"].as_string()).lexically_normal();
    auto& mesh = meshes_[file.string()];
    if (!mesh) {
      try {
        mesh = std::make_shared<const TriangleMesh>(load_obj(file));
      } catch (const InputError& e) {
        n["file"].fail(e.what());  // "scene.json: /shapes/3/file: mesh.obj:12: problem"
      }
    }
    return Mesh{file.string(), mesh, n.has("transform") ? parse_transform(n["transform"]) : Transform{}};
  }

 private:
  std::filesystem::path folder_;
  std::map<std::string, std::shared_ptr<const TriangleMesh>> meshes_;
};

Geometry parse_geometry(const Node& n, const std::string& type, MeshCache& meshes) {
  if (type == "sphere") {
    n.expect_object({"type", "name", "material", "center", "radius"});
    return Sphere{n["center"].as_vec3(), n["radius"].as_positive("radius")};
  }
  if (type == "plane") {
    n.expect_object({"type", "name", "material", "point", "normal"});
    return Plane{n["point"].as_vec3(), n["normal"].as_unit_vector()};
  }
  if (type == "torus") {
    n.expect_object({"type", "name", "material", "center", "axis", "major_radius", "minor_radius"});
    Torus t{n["center"].as_vec3(), Vec3(0, 1, 0), n["major_radius"].as_positive("major_radius"),
            n["minor_radius"].as_positive("minor_radius")};
    if (n.has("axis")) t.axis = n["axis"].as_unit_vector();
    return t;
  }
  if (type == "triangle") {
    n.expect_object({"type", "name", "material", "vertices"});
    return Triangle{parse_vertices<3>(n["vertices"])};
  }
  if (type == "quad") {
    n.expect_object({"type", "name", "material", "vertices"});
    return Quad{parse_vertices<4>(n["vertices"])};
  }
  if (type == "mesh") {
    n.expect_object({"type", "name", "material", "file", "transform"});
    return meshes.load(n);
  }
  if (type == "disk") {
    n.expect_object({"type", "name", "material", "center", "normal", "radius"});
    return Disk{n["center"].as_vec3(), n["normal"].as_unit_vector(), n["radius"].as_positive("radius")};
  }
  n["type"].fail("unknown shape type '" + type + "' (known: sphere, plane, torus, triangle, quad, mesh, disk)");
}

PointLight parse_light(const Node& n) {
  n.expect_object({"type", "position", "intensity"});
  if (n["type"].as_string() != "point")
    n["type"].fail("unknown light type '" + n["type"].as_string() + "' (known: point)");
  return PointLight{n["position"].as_vec3(), n["intensity"].as_color(3.0e38f, "intensity")};
}

}  // namespace

SceneDescription parse_scene(const std::string& text, const std::string& source) {
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::exception& e) {
    // A syntax error (with its byte position) or a number that overflows a double; keep
    // nlohmann's description, drop its "[json.exception...]" tag.
    std::string what = e.what();
    const size_t tag_end = what.find("] ");
    if (tag_end != std::string::npos) what = what.substr(tag_end + 2);
    throw InputError(source + ": malformed JSON: " + what);
  }
  const Node root(json, "", source);
  root.expect_object({"render", "camera", "background", "materials", "shapes", "lights"});

  SceneDescription scene;
  scene.source = source;
  if (root.has("render")) scene.render = parse_render(root["render"]);
  scene.camera = parse_camera(root["camera"]);
  if (root.has("background")) scene.background = root["background"].as_color(3.0e38f, "background radiance");

  std::map<std::string, int> material_index;
  const Node materials = root["materials"];
  materials.expect_object();  // any name; each material is checked below
  for (const auto& item : json["materials"].items()) {
    const Node m(item.value(), "/materials/" + item.key(), scene.source);
    material_index[item.key()] = int(scene.materials.size());
    scene.materials.push_back(parse_material(m, item.key()));
  }

  MeshCache meshes(std::filesystem::path(source).parent_path());
  const Node shapes = root["shapes"];
  const size_t shape_count = shapes.expect_array();
  for (size_t i = 0; i < shape_count; ++i) {
    const Node s = shapes.at(i);
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
    const Node lights = root["lights"];
    const size_t light_count = lights.expect_array();
    for (size_t i = 0; i < light_count; ++i) scene.lights.push_back(parse_light(lights.at(i)));
  }
  return scene;
}

SceneDescription load_scene(const std::filesystem::path& path) {
  return parse_scene(read_input_file(path, "scene file", kMaxSceneFileBytes), path.string());
}

}  // namespace rt
