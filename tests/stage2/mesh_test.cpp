// OBJ meshes (common/obj_loader.h), their placement in the world (stages/02-whitted/mesh_instance.h)
// and the scene file's "mesh" shape.
#include "02-whitted/mesh_instance.h"
#include "02-whitted/whitted_scene.h"
#include "common/error.h"
#include "common/obj_loader.h"

#include "support/test_support.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::ScratchDir;
using testing::source_path;
using testing::subject;
using testing::write_text;

// The message of the InputError that `load` throws, or "" if it throws none.
template <class Load>
std::string error_of(Load&& load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kCubeWithNormals = R"(# a unit cube, quads, a normal per face
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
f 1//1 4//1 3//1 2//1
f 5//2 6//2 7//2 8//2
f 1//3 2//3 6//3 5//3
f 4//4 8//4 7//4 3//4
f 1//5 5//5 8//5 4//5
f 2//6 3//6 7//6 6//6
)";

TEST(ObjLoader, ReadsQuadsAsTriangleFansWithNormals) {
  ScratchDir dir;
  write_text(dir / "cube.obj", kCubeWithNormals);
  const TriangleMesh mesh = load_obj(dir / "cube.obj");
  EXPECT_EQ(mesh.positions.size(), 8u);
  EXPECT_EQ(mesh.normals.size(), 6u);
  ASSERT_EQ(mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 3, 2})) << "fan (c0, c1, c2)";
  EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 1})) << "fan (c0, c2, c3)";
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    ASSERT_TRUE(mesh.has_normals(t));
    // Every face's normal points out of the cube, and agrees with its winding.
    const auto& c = mesh.triangles[t];
    const Vec3 p0 = mesh.positions[c[0]], p1 = mesh.positions[c[1]], p2 = mesh.positions[c[2]];
    const Vec3 geometric = glm::cross(p1 - p0, p2 - p0);
    const Vec3 n = mesh.normals[size_t(mesh.triangle_normals[t][0])];
    EXPECT_GT(glm::dot(geometric, n), 0.0f) << "triangle " << t;
    EXPECT_GT(glm::dot(n, (p0 + p1 + p2) / 3.0f - Vec3(0.5f)), 0.0f) << "triangle " << t;
  }
}

TEST(ObjLoader, ReadsMeshesWithoutNormalsAndRelativeIndices) {
  ScratchDir dir;
  write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf -4 -3 -2\nf 1/1 2/2 3/3\nvt 0 0\nvt 1 0\nvt 0 1\n");
  const TriangleMesh mesh = load_obj(dir / "tri.obj");
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_FALSE(mesh.has_normals(0));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2})) << "negative indices count back";
  EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(ObjLoader, TheShippedIcosphereIsClosedAndFacesOut) {
  const TriangleMesh mesh = load_obj(source_path("assets/meshes/icosphere.obj"));
  EXPECT_EQ(mesh.triangles.size(), 80u);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& c = mesh.triangles[t];
    const Vec3 p0 = mesh.positions[c[0]], p1 = mesh.positions[c[1]], p2 = mesh.positions[c[2]];
    EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), p0 + p1 + p2), 0.0f) << "triangle " << t;
  }
}

struct BrokenObj {
  const char* name;
  const char* text;
  const char* message;  // what follows "FILE:" in the error
};
void PrintTo(const BrokenObj& b, std::ostream* out) { *out << b.name; }

class BrokenObjFiles : public ::testing::TestWithParam<BrokenObj> {};

TEST_P(BrokenObjFiles, FailWithFileLineAndProblem) {
  ScratchDir dir;
  const auto path = dir / "broken.obj";
  write_text(path, GetParam().text);
  const std::string message = error_of([&] { load_obj(path); });
  EXPECT_EQ(message, path.string() + ":" + GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(
    ObjLoader, BrokenObjFiles,
    ::testing::Values(
        BrokenObj{"index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n",
                  "5: vertex index 9 is out of range (the file has 3 vertices)"},
        BrokenObj{"index_zero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                  "4: face corner '0' is not v, v/vt, v/vt/vn or v//vn with non-zero indices (OBJ counts from 1, "
                  "negative indices count back)"},
        BrokenObj{"index_not_a_number", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
                  "4: face corner 'x' is not v, v/vt, v/vt/vn or v//vn with non-zero indices (OBJ counts from 1, "
                  "negative indices count back)"},
        BrokenObj{"normal_index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n",
                  "5: normal index 2 is out of range (the file has 1 normals)"},
        BrokenObj{"nan_vertex", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "2: vertex needs three finite coordinates, got 'nan'"},
        BrokenObj{"infinite_vertex", "v 0 0 0\nv 1 0 0\nv 0 1e40 0\nf 1 2 3\n", "3: vertex needs three finite coordinates, got '1e40'"},
        BrokenObj{"short_vertex", "v 0 0\n", "1: vertex needs three finite coordinates, got '(missing)'"},
        BrokenObj{"zero_normal", "v 0 0 0\nvn 0 0 0\n", "2: normal has zero length"},
        BrokenObj{"nan_texture_coordinate", "v 0 0 0\nvt 0.5 nan\n", "2: texture coordinate needs two finite numbers, got 'nan'"},
        BrokenObj{"short_texture_coordinate", "v 0 0 0\nvt 0.5\n", "2: texture coordinate needs two finite numbers, got '(missing)'"},
        BrokenObj{"texture_index_out_of_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n",
                  "5: texture index 2 is out of range (the file has 1 texture coordinates)"},
        BrokenObj{"two_corner_face", "v 0 0 0\nv 1 0 0\nf 1 2\n", "3: a face needs at least three corners"},
        BrokenObj{"no_faces", "# nothing but vertices\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", " the mesh has no faces"},
        BrokenObj{"empty_file", "", " the mesh has no faces"}),
    [](const auto& info) { return std::string(info.param.name); });

// Texture coordinates ride along like normals: per corner, fanned with the face, and blended by a
// hit's barycentrics; a face whose corners do not all have one gets the barycentrics themselves.
TEST(ObjLoader, ReadsTextureCoordinatesPerCorner) {
  const TriangleMesh mesh = parse_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2 0.5\n"
      "f 1/1 2/2 3/3 4/4\nf 1 3 4\n",
      "uv.obj");
  ASSERT_EQ(mesh.uvs.size(), 4u);
  EXPECT_EQ(mesh.uvs[3], Vec2(0.0f, 2.0f)) << "a third number (w) is ignored";
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_TRUE(mesh.has_uvs(0));
  EXPECT_TRUE(mesh.has_uvs(1));
  EXPECT_FALSE(mesh.has_uvs(2));
  EXPECT_EQ(mesh.uv_at(1, 0.5f, 0.25f), 0.25f * Vec2(0, 0) + 0.5f * Vec2(2, 2) + 0.25f * Vec2(0, 2))
      << "the fan's second triangle is corners 1, 3, 4";
  EXPECT_EQ(mesh.uv_at(2, 0.5f, 0.25f), Vec2(0.5f, 0.25f));
  // A mirroring placement swaps two corners of every triangle: the coordinates must follow.
  const Vec2 mirrored_uv = subject([&] {
    return place_mesh(mesh, Transform::from_scale_rotate_translate(Vec3(-1, 1, 1), Vec3(0), Vec3(0))).uv_at(0, 0.25f, 0.5f);
  });
  EXPECT_EQ(mirrored_uv, mesh.uv_at(0, 0.5f, 0.25f));
}

TEST(ObjLoader, MissingFileIsNamed) {
  EXPECT_EQ(error_of([] { load_obj("/nonexistent/mesh.obj"); }), "/nonexistent/mesh.obj: cannot open mesh file");
}

// A UV sphere squashed by scale (1, 1/4, 1) is an ellipsoid x^2 + (y/b)^2 + z^2 = 1, b = 1/4, whose
// normal at (x, y, z) is parallel to the gradient (x, y / b^2, z). Transforming the sphere's
// normals by M itself would give (x, b y, z): tilted towards the flat equator, visibly wrong.
TEST(MeshPlacement, NormalsUseTheInverseTranspose) {
  TriangleMesh sphere = make_uv_sphere(8, 16, 0.0f, 1);
  sphere.normals = sphere.positions;  // a unit sphere's normals are its positions
  sphere.triangle_normals.clear();
  for (const auto& c : sphere.triangles) sphere.triangle_normals.push_back({std::int32_t(c[0]), std::int32_t(c[1]), std::int32_t(c[2])});
  const float b = 0.25f;
  const Transform squash = Transform::from_scale_rotate_translate(Vec3(1, b, 1), Vec3(0, 30, 0), Vec3(3, 1, 2));
  const auto [normals, first_position] = subject([&] {
    const TriangleMesh placed = place_mesh(sphere, squash);
    return std::pair(placed.normals, placed.positions.at(0));
  });
  ASSERT_EQ(normals.size(), sphere.positions.size());
  const glm::mat3 rotation = Transform::from_scale_rotate_translate(Vec3(1), Vec3(0, 30, 0), Vec3(0)).linear();
  for (size_t i = 0; i < sphere.positions.size(); ++i) {
    // The analytic normal, rotated like the ellipsoid.
    const Vec3 p = sphere.positions[i];
    // The squashed point is (x, b y, z); the gradient there is (x, b y / b^2, z) = (x, y / b, z).
    const Vec3 gradient_local(p.x, p.y / b, p.z);
    const Vec3 analytic = glm::normalize(rotation * gradient_local);
    EXPECT_NEAR(glm::length(normals[i] - analytic), 0.0f, 1e-5f) << "vertex " << i;
    EXPECT_NEAR(glm::length(normals[i]), 1.0f, 1e-6f);
  }
  EXPECT_EQ(first_position, squash.point(sphere.positions[0]));
}

TEST(MeshPlacement, MirroringScaleKeepsTrianglesFacingOut) {
  const TriangleMesh sphere = make_uv_sphere(6, 12, 0.2f, 3);
  const Transform mirror = Transform::from_scale_rotate_translate(Vec3(-2, 1, 1), Vec3(0), Vec3(0));
  const std::vector<std::array<Vec3, 3>> corners = subject([&] {
    const TriangleMesh placed = place_mesh(sphere, mirror);
    std::vector<std::array<Vec3, 3>> each;
    for (const auto& c : placed.triangles) each.push_back({placed.positions[c[0]], placed.positions[c[1]], placed.positions[c[2]]});
    return each;
  });
  EXPECT_EQ(corners.size(), sphere.triangles.size());
  for (const auto& [p0, p1, p2] : corners) {
    EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), p0 + p1 + p2), 0.0f);
  }
}

TEST(MeshPlacement, TransformAppliesScaleThenRotationThenTranslation) {
  const Transform t = Transform::from_scale_rotate_translate(Vec3(2, 3, 4), Vec3(0, 90, 0), Vec3(10, 20, 30));
  // (1, 1, 1) scaled -> (2, 3, 4); rotated 90 degrees about +y: (x, y, z) -> (z, y, -x) = (4, 3, -2).
  const Vec3 p = t.point(Vec3(1));
  EXPECT_NEAR(p.x, 14.0f, 1e-5f);
  EXPECT_NEAR(p.y, 23.0f, 1e-5f);
  EXPECT_NEAR(p.z, 28.0f, 1e-5f);
}

TEST(MeshPlacement, QuadsSplitAlongTheFirstDiagonal) {
  const Quad quad{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0.5f), Vec3(0, 1, 0)}};  // not planar
  const TriangleMesh mesh = mesh_from_quad(quad);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  // The split defines the surface: a ray through (0.75, 0.25) meets triangle 0's plane.
  SceneDescription d;
  d.materials.push_back(Material{});
  d.shapes.push_back(Shape{"quad", quad, 0});
  const auto hit = subject([&] { return WhittedScene(d).closest_hit(Ray{Vec3(0.75f, 0.25f, -1), Vec3(0, 0, 1)}, Interval::positive()); });
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->triangle, 0);
  EXPECT_NEAR(hit->point.z, 0.125f, 1e-6f);  // plane z = y / 2 there
}

TEST(MeshPlacement, InterpolatedShadingNormalMatchesTheSphere) {
  // The icosphere's vertex normals are exact sphere normals, so the interpolated normal at any
  // hit is close to the direction from the centre; the geometric (flat) one is not as close.
  const std::string scene_text = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30},
    "materials": {"m": {}}, "shapes": [{"type": "mesh", "file": "meshes/icosphere.obj", "material": "m"}]})";
  const SceneDescription d = parse_scene(scene_text, source_path("assets/scene.json").string());
  const WhittedScene scene(d);
  double flat_error = 0, smooth_error = 0;
  for (int i = -7; i <= 7; ++i)
    for (int j = -7; j <= 7; ++j) {
      if (i * i + j * j > 49) continue;  // inside radius 0.7, well within the silhouette
      const auto hit = subject([&] { return scene.closest_hit(Ray{Vec3(0.1f * i, 0.1f * j, -5), Vec3(0, 0, 1)}, Interval::positive()); });
      ASSERT_TRUE(hit);
      const Vec3 radial = glm::normalize(hit->point);
      smooth_error += glm::length(hit->shading_normal - radial);
      flat_error += glm::length(hit->normal - radial);
    }
  EXPECT_LT(smooth_error, 0.5 * flat_error);
}

TEST(SceneMeshes, ResolveFilesNextToTheSceneAndReportBadOnes) {
  ScratchDir dir;
  std::filesystem::create_directories(dir / "meshes");
  write_text(dir / "meshes" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_text(dir / "meshes" / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  auto scene_with = [](const std::string& file, const std::string& transform) {
    return R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30}, "materials": {"m": {}},
      "shapes": [{"type": "mesh", "file": ")" + file + R"(", "material": "m")" + transform + "}]}";
  };
  const SceneDescription ok = parse_scene(scene_with("meshes/tri.obj", R"(, "transform": {"scale": 2, "translate": [1, 0, 0]})"),
                                          (dir / "scene.json").string());
  const auto& mesh = std::get<Mesh>(ok.shapes[0].geometry);
  EXPECT_EQ(mesh.mesh->triangles.size(), 1u);
  EXPECT_EQ(mesh.transform.point(Vec3(0, 1, 0)), Vec3(1, 2, 0));

  const std::string scene_file = (dir / "scene.json").string();
  EXPECT_EQ(error_of([&] { parse_scene(scene_with("meshes/bad.obj", ""), scene_file); }),
            scene_file + ": /shapes/0/file: " + (dir / "meshes" / "bad.obj").string() +
                ":4: vertex index 4 is out of range (the file has 3 vertices)");
  EXPECT_EQ(error_of([&] { parse_scene(scene_with("meshes/none.obj", ""), scene_file); }),
            scene_file + ": /shapes/0/file: " + (dir / "meshes" / "none.obj").string() + ": cannot open mesh file");
  EXPECT_EQ(error_of([&] { parse_scene(scene_with("meshes/tri.obj", R"(, "transform": {"scale": [1, 0, 1]})"), scene_file); }),
            scene_file + ": /shapes/0/transform/scale: scale must not be zero on any axis (the mesh would be flat)");
  EXPECT_EQ(error_of([&] { parse_scene(scene_with("meshes/tri.obj", R"(, "transform": {"shear": 1})"), scene_file); }),
            scene_file + ": /shapes/0/transform: unknown key 'shear'");
}

}  // namespace
}  // namespace rt
