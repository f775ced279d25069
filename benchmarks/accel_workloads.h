// Workloads shared by the stage-3 measurements (stage3_bench and accel_scaling): meshes of a given
// size, coherent and incoherent rays, and, when Debian's libembree-dev is installed, Embree on the
// same mesh and rays as the production ceiling.
#pragma once

#include "02-whitted/mesh_instance.h"
#include "02-whitted/whitted_scene.h"
#include "03-acceleration/bvh_aggregate.h"
#include "common/error.h"
#include "common/random.h"
#include "common/scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#if RT_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace rt::bench {

// A jittered UV sphere with about `triangles` triangles (2 s (s/2 - 1) for s segments).
// The measurements search stage 2's kinds; their workloads are one triangle mesh each.
using Primitives = WhittedPrimitives;

inline std::shared_ptr<Primitives> single_mesh(TriangleMesh mesh) {
  auto set = std::make_shared<Primitives>();
  set->store_of<TriangleKind>().add_mesh(std::move(mesh), 0, 0);
  return set;
}

inline std::shared_ptr<Primitives> sphere_mesh(double triangles) {
  const int segments = std::max(8, int(std::lround(std::sqrt(triangles))));
  return single_mesh(make_uv_sphere(std::max(3, segments / 2), segments, 0.2f, 17));
}

inline const TriangleMesh& the_mesh(const Primitives& set) { return set.store_of<TriangleKind>().meshes[0].geometry; }

inline Aabb mesh_bounds(const Primitives& set) {
  Aabb box;
  for (const Vec3& p : the_mesh(set).positions) box.expand(p);
  return box;
}

// Incoherent: from random points on a sphere around the mesh to random points in its box.
inline std::vector<Ray> incoherent_rays(const Primitives& set, int count, std::uint64_t seed = 1) {
  const Aabb box = mesh_bounds(set);
  const float radius = glm::length(box.extent());
  Rng rng(seed, 0, 0);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3 u = glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f);
    const Vec3 origin = box.centroid() + radius * u;
    const Vec3 target = box.lo + Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * box.extent();
    rays.push_back(Ray{origin, glm::normalize(target - origin)});
  }
  return rays;
}

// Coherent: the rays of a side x side pinhole camera looking at the mesh, row by row.
inline std::vector<Ray> coherent_rays(const Primitives& set, int side) {
  const Aabb box = mesh_bounds(set);
  const Vec3 eye = box.centroid() + Vec3(0.3f, 0.4f, -1.0f) * glm::length(box.extent());
  const Vec3 forward = glm::normalize(box.centroid() - eye), right = glm::normalize(glm::cross(forward, Vec3(0, 1, 0)));
  const Vec3 up = glm::cross(right, forward);
  std::vector<Ray> rays;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const float sx = (2.0f * (float(x) + 0.5f) / float(side) - 1.0f) * 0.3f;
      const float sy = (1.0f - 2.0f * (float(y) + 0.5f) / float(side)) * 0.3f;
      rays.push_back(Ray{eye, glm::normalize(forward + sx * right + sy * up)});
    }
  return rays;
}

// The rays a path tracer traces in a closed scene (the Cornell box): from points spread over the
// surfaces by area, a bounce ray cosine-distributed about the normal turned to the scene's centre,
// and a shadow ray to a point of the emitters (the shapes whose material emits), which ends just
// short of it. The scene's triangles are one mesh, so that Embree gets the same geometry.
struct PathRays {
  std::shared_ptr<Primitives> scene;
  std::vector<Ray> bounce, shadow;
  std::vector<float> shadow_length;
};

inline PathRays path_rays(const std::filesystem::path& scene_file, int count, std::uint64_t seed = 1) {
  const SceneDescription description = load_scene(scene_file);
  TriangleMesh all, lights;
  for (const Shape& shape : description.shapes) {
    const std::optional<TriangleMesh> mesh = triangles_of(shape.geometry);
    if (!mesh) throw InputError(description.source + ": path_rays takes scenes of triangles and quads");
    const auto append_to = [&mesh](TriangleMesh& into) {
      const auto base = std::uint32_t(into.positions.size());
      into.positions.insert(into.positions.end(), mesh->positions.begin(), mesh->positions.end());
      for (const auto& t : mesh->triangles) into.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    };
    append_to(all);
    if (max_component(description.materials[size_t(shape.material)].emission) > 0.0f) append_to(lights);
  }
  Rng rng(seed, 0, 0);
  // A point spread over a mesh by area, with its triangle's unit normal.
  const auto by_area = [&rng](const TriangleMesh& mesh, const std::vector<double>& cumulative_area) {
    const double u = double(rng.uniform()) * cumulative_area.back();
    const size_t k = std::min(size_t(std::lower_bound(cumulative_area.begin(), cumulative_area.end(), u) -
                                     cumulative_area.begin()),
                              cumulative_area.size() - 1);
    const auto& t = mesh.triangles[k];
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const float r = std::sqrt(rng.uniform()), s = rng.uniform();  // uniform on the triangle
    return std::pair{(1.0f - r) * a + r * (1.0f - s) * b + r * s * c, glm::normalize(glm::cross(b - a, c - a))};
  };
  const auto cumulative_area = [](const TriangleMesh& mesh) {
    std::vector<double> sums;
    double total = 0.0;
    for (const auto& t : mesh.triangles) {
      const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
      sums.push_back(total += 0.5 * double(glm::length(glm::cross(b - a, c - a))));
    }
    return sums;
  };
  const std::vector<double> all_areas = cumulative_area(all), light_areas = cumulative_area(lights);
  if (light_areas.empty()) throw InputError(description.source + ": path_rays needs an emitting shape");
  Aabb box;
  for (const Vec3& p : all.positions) box.expand(p);
  PathRays rays;
  for (int i = 0; i < count; ++i) {
    auto [p, normal] = by_area(all, all_areas);
    if (glm::dot(box.centroid() - p, normal) < 0.0f) normal = -normal;
    Vec3 u;  // uniform in the unit ball, then on the sphere: normal + u is cosine-distributed
    do u = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f;
    while (glm::dot(u, u) > 1.0f || glm::dot(u, u) < 1e-4f);
    const Vec3 origin = p + 1e-5f * glm::length(box.extent()) * normal;
    rays.bounce.push_back(Ray{origin, glm::normalize(normal + glm::normalize(u))});
    const Vec3 to_light = by_area(lights, light_areas).first - origin;
    rays.shadow.push_back(Ray{origin, glm::normalize(to_light)});
    rays.shadow_length.push_back(0.999f * glm::length(to_light));
  }
  rays.scene = single_mesh(std::move(all));
  return rays;
}

#if RT_HAVE_EMBREE
// Embree 3 over one triangle mesh, default (medium) build quality, one ray at a time.
class EmbreeMesh {
 public:
  explicit EmbreeMesh(const TriangleMesh& mesh) : device_(rtcNewDevice(nullptr)) {
    // Every allocation the device makes from here on is counted: its copy of the mesh and its BVH.
    rtcSetDeviceMemoryMonitorFunction(
        device_,
        [](void* bytes, ssize_t change, bool) {
          *static_cast<std::atomic<std::int64_t>*>(bytes) += change;  // from the build's threads
          return true;
        },
        &bytes_);
    scene_ = rtcNewScene(device_);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vertices[3 * i + size_t(k)] = mesh.positions[i][k];
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.triangles.size()));
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) indices[3 * i + size_t(k)] = mesh.triangles[i][size_t(k)];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
  }
  ~EmbreeMesh() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeMesh(const EmbreeMesh&) = delete;
  EmbreeMesh& operator=(const EmbreeMesh&) = delete;

  // The memory the device holds: its mesh (vertices and indices) and its BVH, as Embree reports them.
  size_t bytes() const { return size_t(bytes_.load()); }

  std::optional<float> closest_hit(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray.org_x = ray.origin.x, query.ray.org_y = ray.origin.y, query.ray.org_z = ray.origin.z;
    query.ray.dir_x = ray.direction.x, query.ray.dir_y = ray.direction.y, query.ray.dir_z = ray.direction.z;
    query.ray.tnear = 0.0f;
    query.ray.tfar = kInfinity;
    query.ray.mask = ~0u;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return query.ray.tfar;
  }
  bool occluded(const Ray& ray, float t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay query{};
    query.org_x = ray.origin.x, query.org_y = ray.origin.y, query.org_z = ray.origin.z;
    query.dir_x = ray.direction.x, query.dir_y = ray.direction.y, query.dir_z = ray.direction.z;
    query.tnear = 0.0f;
    query.tfar = t_max;
    query.mask = ~0u;
    rtcOccluded1(scene_, &context, &query);
    return query.tfar < 0.0f;  // Embree sets tfar to -inf when it finds a hit
  }

 private:
  // Before device_: the monitor writes to it from the device's first allocation on.
  std::atomic<std::int64_t> bytes_{0};
  RTCDevice device_;
  RTCScene scene_ = nullptr;
};
#endif

}  // namespace rt::bench
