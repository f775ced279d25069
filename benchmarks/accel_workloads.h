// Workloads shared by the stage-3 measurements (stage3_bench and accel_scaling): meshes of a given
// size, coherent and incoherent rays, and, when Debian's libembree-dev is installed, Embree on the
// same mesh and rays as the production ceiling.
#pragma once

#include "02-whitted/whitted_scene.h"
#include "03-acceleration/bvh_aggregate.h"
#include "common/random.h"

#include <atomic>
#include <cmath>
#include <cstdint>
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

 private:
  // Before device_: the monitor writes to it from the device's first allocation on.
  std::atomic<std::int64_t> bytes_{0};
  RTCDevice device_;
  RTCScene scene_ = nullptr;
};
#endif

}  // namespace rt::bench
