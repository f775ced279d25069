#include "common/error.h"
#include "common/scene.h"

#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::source_path;

TEST(SceneLoader, LoadsTheSpheresScene) {
  const SceneDescription scene = load_scene(source_path("assets/scenes/spheres.json"));
  EXPECT_EQ(scene.render.width, 640);
  EXPECT_EQ(scene.render.height, 400);
  ASSERT_EQ(scene.shapes.size(), 5u);
  EXPECT_TRUE(std::holds_alternative<Plane>(scene.shapes[0].geometry));
  const auto& ring = std::get<Torus>(scene.shapes[4].geometry);
  EXPECT_NEAR(glm::length(ring.axis), 1.0f, 1e-6f) << "axes are normalized on load";
  EXPECT_EQ(scene.lights.size(), 2u);
}

// docs/design.md's canonical Cornell box, checked against the numbers it gives.
class CornellBox : public ::testing::Test {
 protected:
  SceneDescription scene = load_scene(source_path("assets/scenes/cornell-box.json"));

  const Shape& shape(const std::string& name) const {
    for (const Shape& s : scene.shapes)
      if (s.name == name) return s;
    throw std::runtime_error("no shape " + name);
  }
  const Material& material_of(const std::string& name) const {
    return scene.materials[size_t(shape(name).material)];
  }
  // The normals of the two triangles (v0,v1,v2) and (v0,v2,v3) the quad is meshed into.
  static std::array<Vec3, 2> triangle_normals(const Quad& q) {
    const auto& v = q.vertices;
    return {glm::cross(v[1] - v[0], v[2] - v[0]), glm::cross(v[2] - v[0], v[3] - v[0])};
  }
  static Vec3 centroid(const Quad& q) {
    return 0.25f * (q.vertices[0] + q.vertices[1] + q.vertices[2] + q.vertices[3]);
  }
};

TEST_F(CornellBox, CameraMaterialsAndLight) {
  EXPECT_EQ(scene.camera.position, Vec3(278, 273, -800));
  EXPECT_EQ(scene.camera.look_at, Vec3(278, 273, 0));
  EXPECT_FLOAT_EQ(scene.camera.vfov_degrees, 39.3077f);
  EXPECT_EQ(scene.render.width, scene.render.height) << "square image";
  EXPECT_EQ(scene.background, Color(0.0f));
  EXPECT_EQ(material_of("floor").albedo, Color(0.725f, 0.71f, 0.68f));
  EXPECT_EQ(material_of("left wall").albedo, Color(0.63f, 0.065f, 0.05f)) << "left wall is red";
  EXPECT_EQ(material_of("right wall").albedo, Color(0.14f, 0.45f, 0.091f)) << "right wall is green";
  EXPECT_EQ(material_of("light").albedo, Color(0.65f));
  EXPECT_EQ(material_of("light").emission, Color(47.8348f, 38.5664f, 31.0808f));
  EXPECT_EQ(scene.shapes.size(), 16u) << "6 room quads + 5 faces per block";
  for (const Shape& s : scene.shapes)
    if (s.name != "light") {
      EXPECT_EQ(scene.materials[size_t(s.material)].emission, Color(0.0f)) << s.name;
    }
}

TEST_F(CornellBox, RoomFacesInwardAndLightFacesDown) {
  const Vec3 room_centre(278.0f, 274.4f, 279.6f);
  for (const char* name : {"floor", "ceiling", "back wall", "right wall", "left wall"}) {
    const Quad& q = std::get<Quad>(shape(name).geometry);
    for (const Vec3& n : triangle_normals(q))
      EXPECT_GT(glm::dot(n, room_centre - centroid(q)), 0.0f) << name << " must face into the box";
  }
  const Quad& light = std::get<Quad>(shape("light").geometry);
  for (const Vec3& n : triangle_normals(light)) {
    EXPECT_LT(glm::normalize(n).y, -0.9999f) << "the light faces -y";
  }
  for (const Vec3& v : light.vertices) EXPECT_FLOAT_EQ(v.y, 548.7f);
}

TEST_F(CornellBox, BlockFacesFaceOutward) {
  for (const char* block : {"short block", "tall block"}) {
    std::vector<const Quad*> faces;
    Vec3 block_centre(0.0f);
    for (const Shape& s : scene.shapes)
      if (s.name.rfind(block, 0) == 0) faces.push_back(&std::get<Quad>(s.geometry));
    ASSERT_EQ(faces.size(), 5u) << block;
    for (const Quad* q : faces) block_centre += centroid(*q);
    block_centre /= 5.0f;
    for (const Quad* q : faces) {
      for (const Vec3& n : triangle_normals(*q))
        EXPECT_GT(glm::dot(n, centroid(*q) - block_centre), 0.0f) << block << " face must face out";
      for (const Vec3& v : q->vertices) EXPECT_TRUE(v.y == 0.0f || v.y == 165.0f || v.y == 330.0f);
    }
  }
}

TEST_F(CornellBox, RedWallIsNotPlanar) {
  // The red wall's two triangles are 0.468 degrees apart (computed in double; docs/design.md),
  // which is why the triangulation (v0,v1,v2)+(v0,v2,v3) is part of the scene.
  const auto n = triangle_normals(std::get<Quad>(shape("left wall").geometry));
  const float degrees = std::acos(glm::dot(glm::normalize(n[0]), glm::normalize(n[1]))) * 180.0f / kPi;
  EXPECT_NEAR(degrees, 0.468f, 0.005f);
}

TEST(SceneLoader, DefaultsForEverythingAMinimalSceneLeavesOut) {
  const SceneDescription scene = parse_scene(
      R"({"camera": {"position": [0,0,0], "look_at": [0,0,1], "vfov": 45},
          "materials": {"m": {}},
          "shapes": [{"type": "sphere", "center": [0,0,5], "radius": 1, "material": "m"}]})",
      "minimal.json");
  const RenderSettings defaults;
  EXPECT_EQ(scene.render.width, defaults.width);
  EXPECT_EQ(scene.render.spp, defaults.spp);
  EXPECT_EQ(scene.camera.up, Vec3(0, 1, 0));
  EXPECT_EQ(scene.materials[0].albedo, Color(0.8f));
  EXPECT_EQ(scene.materials[0].specular, Color(0.0f));
  EXPECT_TRUE(scene.lights.empty());
}

// Each broken scene must fail with an InputError whose message names the file, the JSON path and
// the problem.
struct BrokenScene {
  const char* what;
  std::string json;
  std::string expected_message;
};

const std::string kCamera = R"("camera": {"position": [0,0,0], "look_at": [0,0,1], "vfov": 45})";
const std::string kMaterials = R"("materials": {"m": {"albedo": [0.5, 0.5, 0.5]}})";
std::string scene_with_shape(const std::string& shape) {
  return "{" + kCamera + ", " + kMaterials + R"(, "shapes": [)" + shape + "]}";
}
const std::string kSphere = R"({"type": "sphere", "center": [0,0,5], "radius": 1, "material": "m"})";

// Names the case in test listings instead of dumping its bytes.
void PrintTo(const BrokenScene& c, std::ostream* out) { *out << c.what; }

class BrokenSceneTest : public ::testing::TestWithParam<BrokenScene> {};

TEST_P(BrokenSceneTest, FailsWithAClearMessage) {
  const BrokenScene& c = GetParam();
  try {
    parse_scene(c.json, "broken.json");
    FAIL() << c.what << ": accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("broken.json: ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected_message), std::string::npos)
        << c.what << "\n  got:      " << message << "\n  expected: " << c.expected_message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line only";
  }
}

INSTANTIATE_TEST_SUITE_P(
    SceneLoader, BrokenSceneTest,
    ::testing::Values(
        BrokenScene{"malformed JSON", R"({"camera": )", "malformed JSON"},
        BrokenScene{"NaN literal", scene_with_shape(R"({"type": "sphere", "center": [0,0,NaN], "radius": 1, "material": "m"})"),
                    "malformed JSON"},
        BrokenScene{"not an object", "[1, 2]", "/: expected an object, got array"},
        BrokenScene{"missing camera", "{" + kMaterials + R"(, "shapes": []})", "/: missing field 'camera'"},
        BrokenScene{"missing radius", scene_with_shape(R"({"type": "sphere", "center": [0,0,5], "material": "m"})"),
                    "/shapes/0: missing field 'radius'"},
        BrokenScene{"wrong type", scene_with_shape(R"({"type": "sphere", "center": [0,0,5], "radius": "big", "material": "m"})"),
                    "/shapes/0/radius: expected a number, got string"},
        BrokenScene{"negative radius", scene_with_shape(R"({"type": "sphere", "center": [0,0,5], "radius": -1, "material": "m"})"),
                    "/shapes/0/radius: radius must be positive, got -1"},
        BrokenScene{"overflowing number", scene_with_shape(R"({"type": "sphere", "center": [0,0,1e999], "radius": 1, "material": "m"})"),
                    "malformed JSON: number overflow parsing '1e999'"},
        BrokenScene{"beyond float range", scene_with_shape(R"({"type": "sphere", "center": [0,0,1e300], "radius": 1, "material": "m"})"),
                    "/shapes/0/center/2: the number 1e+300 is beyond float's range"},
        BrokenScene{"unknown material", scene_with_shape(R"({"type": "sphere", "center": [0,0,5], "radius": 1, "material": "gold"})"),
                    "/shapes/0/material: unknown material 'gold'"},
        BrokenScene{"unknown shape", scene_with_shape(R"({"type": "cube", "material": "m"})"),
                    "/shapes/0/type: unknown shape type 'cube'"},
        BrokenScene{"misspelt key", scene_with_shape(R"({"type": "sphere", "center": [0,0,5], "radius": 1, "radus": 2, "material": "m"})"),
                    "/shapes/0: unknown key 'radus'"},
        BrokenScene{"short vector", scene_with_shape(R"({"type": "sphere", "center": [0,5], "radius": 1, "material": "m"})"),
                    "/shapes/0/center: expected an array of 3 numbers"},
        BrokenScene{"three-cornered quad", scene_with_shape(R"({"type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0]], "material": "m"})"),
                    "/shapes/0/vertices: expected 4 vertices"},
        BrokenScene{"zero plane normal", scene_with_shape(R"({"type": "plane", "point": [0,0,0], "normal": [0,0,0], "material": "m"})"),
                    "/shapes/0/normal: direction must not be zero"},
        BrokenScene{"albedo above one", "{" + kCamera + R"(, "materials": {"m": {"albedo": [0.5, 1.5, 0.5]}}, "shapes": []})",
                    "/materials/m/albedo/1: albedo (more than 1 creates energy) must be in [0, 1], got 1.5"},
        BrokenScene{"unknown material type", "{" + kCamera + R"(, "materials": {"m": {"type": "velvet"}}, "shapes": []})",
                    "/materials/m/type: unknown material type 'velvet'"},
        BrokenScene{"field of view", R"({"camera": {"position": [0,0,0], "look_at": [0,0,1], "vfov": 180}, )" + kMaterials + R"(, "shapes": []})",
                    "/camera/vfov: vertical field of view must be in (0, 180) degrees"},
        BrokenScene{"camera looks at itself", R"({"camera": {"position": [1,1,1], "look_at": [1,1,1], "vfov": 40}, )" + kMaterials + R"(, "shapes": []})",
                    "/camera/look_at: look_at equals position"},
        BrokenScene{"up along view", R"({"camera": {"position": [0,0,0], "look_at": [0,3,0], "vfov": 40}, )" + kMaterials + R"(, "shapes": []})",
                    "/camera: the default up (0, 1, 0) is parallel to the view direction"},
        BrokenScene{"up along view given", R"({"camera": {"position": [0,0,0], "look_at": [0,3,0], "up": [0,-2,0], "vfov": 40}, )" + kMaterials + R"(, "shapes": []})",
                    "/camera/up: up must not be parallel to the view direction"},
        BrokenScene{"zero spp", "{" + kCamera + ", " + kMaterials + R"(, "shapes": [], "render": {"spp": 0}})",
                    "/render/spp: must be in [1, 1048576], got 0"},
        BrokenScene{"absurd width", "{" + kCamera + ", " + kMaterials + R"(, "shapes": [], "render": {"width": 2000000}})",
                    "/render/width: must be in [1, 1048576], got 2000000"},
        BrokenScene{"fractional spp", "{" + kCamera + ", " + kMaterials + R"(, "shapes": [], "render": {"spp": 2.5}})",
                    "/render/spp: expected an integer, got number"},
        BrokenScene{"unknown light", "{" + kCamera + ", " + kMaterials + R"(, "shapes": [], "lights": [{"type": "spot", "position": [0,0,0], "intensity": [1,1,1]}]})",
                    "/lights/0/type: unknown light type 'spot'"},
        BrokenScene{"albedo on a mirror", "{" + kCamera + R"(, "materials": {"m": {"type": "mirror", "albedo": [1,1,1]}}, "shapes": []})",
                    "/materials/m: unknown key 'albedo'"},
        BrokenScene{"index of refraction below one", "{" + kCamera + R"(, "materials": {"m": {"type": "dielectric", "ior": 0.5}}, "shapes": []})",
                    "/materials/m/ior: index of refraction must be in [1, 10], got 0.5"},
        BrokenScene{"mirror reflecting more than it gets", "{" + kCamera + R"(, "materials": {"m": {"type": "mirror", "reflectance": [1,1,1.2]}}, "shapes": []})",
                    "/materials/m/reflectance/2: reflectance (more than 1 creates energy) must be in [0, 1], got 1.2"},
        BrokenScene{"checker of size zero", "{" + kCamera + R"(, "materials": {"m": {"checker": {"albedo": [1,1,1], "size": 0}}}, "shapes": []})",
                    "/materials/m/checker/size: checker size must be positive, got 0"},
        BrokenScene{"phong reflecting more than it gets", "{" + kCamera + R"(, "materials": {"m": {"type": "phong", "albedo": [0.7,0.7,0.7], "specular": [0.2,0.4,0.2]}}, "shapes": []})",
                    "/materials/m: albedo + specular exceeds 1 in some channel"},
        BrokenScene{"phong checker reflecting more than it gets", "{" + kCamera + R"(, "materials": {"m": {"type": "phong", "albedo": [0.2,0.2,0.2], "specular": [0.2,0.2,0.2], "checker": {"albedo": [0.9,0.5,0.5], "size": 1}}}, "shapes": []})",
                    "/materials/m: albedo + specular exceeds 1 in some channel"},
        BrokenScene{"microfacet without roughness", "{" + kCamera + R"(, "materials": {"m": {"type": "microfacet", "roughness": 0}}, "shapes": []})",
                    "/materials/m/roughness: roughness (GGX alpha) must be in [0.001, 1], got 0"},
        BrokenScene{"disk of radius zero", scene_with_shape(R"({"type": "disk", "center": [0,0,0], "normal": [0,1,0], "radius": 0, "material": "m"})"),
                    "/shapes/0/radius: radius must be positive, got 0"},
        BrokenScene{"mesh without a file", scene_with_shape(R"({"type": "mesh", "material": "m"})"), "/shapes/0: missing field 'file'"},
        BrokenScene{"negative intensity", "{" + kCamera + ", " + kMaterials + R"(, "shapes": [], "lights": [{"type": "point", "position": [0,0,0], "intensity": [1,-1,1]}]})",
                    "/lights/0/intensity/1: intensity must be in [0"}),
    [](const auto& info) {
      std::string name = info.param.what;
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

TEST(SceneLoader, MaterialTypesAndTheirDefaults) {
  const SceneDescription scene = parse_scene(
      "{" + kCamera + R"(, "materials": {
          "plain": {},
          "tiles": {"albedo": [1, 0, 0], "checker": {"albedo": [0, 0, 1], "size": 0.5}},
          "silver": {"type": "mirror"},
          "tinted": {"type": "mirror", "reflectance": [0.9, 0.8, 0.7]},
          "glass": {"type": "dielectric"},
          "diamond": {"type": "dielectric", "ior": 2.42},
          "plastic": {"type": "phong", "albedo": [0.3, 0.3, 0.3], "shininess": 50},
          "copper": {"type": "microfacet"},
          "steel": {"type": "microfacet", "specular": [0.6, 0.6, 0.6], "roughness": 0.05}},
        "shapes": [{"type": "disk", "center": [0, 2, 0], "normal": [0, -3, 0], "radius": 0.5, "material": "plain"}]})",
      "materials.json");
  auto material = [&](const std::string& name) {
    for (const Material& m : scene.materials)
      if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
  };
  EXPECT_EQ(material("plain").type, MaterialType::diffuse);
  EXPECT_FALSE(material("plain").checker);
  ASSERT_TRUE(material("tiles").checker);
  EXPECT_EQ(material("tiles").checker->size, 0.5f);
  EXPECT_EQ(material("tiles").albedo_at(Vec3(0.6f, 0, 0)), Color(0, 0, 1));
  EXPECT_EQ(material("silver").type, MaterialType::mirror);
  EXPECT_EQ(material("silver").reflectance, Color(1.0f));
  EXPECT_EQ(material("tinted").reflectance, Color(0.9f, 0.8f, 0.7f));
  EXPECT_EQ(material("glass").type, MaterialType::dielectric);
  EXPECT_EQ(material("glass").ior, 1.5f);
  EXPECT_EQ(material("diamond").ior, 2.42f);
  EXPECT_EQ(material("plastic").type, MaterialType::phong);
  EXPECT_EQ(material("plastic").specular, Color(0.2f));
  EXPECT_EQ(material("plastic").shininess, 50.0f);
  EXPECT_EQ(material("copper").type, MaterialType::microfacet);
  EXPECT_EQ(material("copper").roughness, 0.2f);
  EXPECT_EQ(material("steel").specular, Color(0.6f));
  EXPECT_EQ(material("steel").roughness, 0.05f);
  const auto& disk = std::get<Disk>(scene.shapes.at(0).geometry);
  EXPECT_EQ(disk.normal, Vec3(0, -1, 0));
  EXPECT_EQ(disk.radius, 0.5f);
}

TEST(SceneLoader, PointLightCornellBoxHasTheCanonicalGeometry) {
  // Stage 2's Cornell box adds only a point light at the centre of the emitter, with the
  // emitter's on-axis intensity I = Le * A (A = 130 mm x 105 mm).
  const SceneDescription canonical = load_scene(testing::source_path("assets/scenes/cornell-box.json"));
  const SceneDescription lit = load_scene(testing::source_path("assets/scenes/cornell-box-point-light.json"));
  ASSERT_EQ(lit.shapes.size(), canonical.shapes.size());
  for (size_t i = 0; i < lit.shapes.size(); ++i) {
    EXPECT_EQ(lit.shapes[i].name, canonical.shapes[i].name);
    EXPECT_EQ(std::get<Quad>(lit.shapes[i].geometry).vertices, std::get<Quad>(canonical.shapes[i].geometry).vertices);
  }
  ASSERT_EQ(lit.lights.size(), 1u);
  EXPECT_EQ(lit.lights[0].position, Vec3(278, 548.7f, 279.5f));
  EXPECT_NEAR(lit.lights[0].intensity.r, 47.8348f * 130 * 105, 0.1f);
  EXPECT_NEAR(lit.lights[0].intensity.b, 31.0808f * 130 * 105, 0.1f);
}

TEST(SceneLoader, MissingFileIsNamed) {
  try {
    load_scene("no/such/scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "no/such/scene.json: cannot open scene file");
  }
}

}  // namespace
}  // namespace rt
