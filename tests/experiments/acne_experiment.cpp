#include "experiments/acne_experiment.h"

#include "01-ray-casting/camera_rays.h"
#include "02-whitted/whitted_scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <optional>

namespace rt {
namespace {

// The scene in its own units, before scaling: plane y = 0, sphere of radius 1 at height 1.3,
// light up and to the side.
constexpr double kSphereHeight = 1.3;
const DVec3 kLight(2.5, 6.0, -1.5);
const DVec3 kCameraPosition(0.0, 3.0, -7.0);
const DVec3 kCameraTarget(0.0, 0.6, 0.0);
constexpr double kGuard = 1e-3;  // of the sphere's radius

// World = scale * (R * local + t): a rotation about a skew axis and a translation of 0.3.
struct Placement {
  glm::dmat3 rotation;
  DVec3 translation;
  double scale;

  DVec3 to_world(DVec3 local) const { return scale * (rotation * local + translation); }
  DVec3 to_local(DVec3 world) const { return glm::transpose(rotation) * (world / scale - translation); }
  DVec3 direction_to_local(DVec3 d) const { return glm::transpose(rotation) * d; }
};

Placement placement(double scale) {
  const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), glm::radians(25.0), glm::normalize(DVec3(1, 2, 3)));
  return Placement{glm::dmat3(r), DVec3(0.3, -0.3, 0.3), scale};
}

// Smallest t > 0 where the double ray meets the unit sphere at (0, h, 0), or nothing.
std::optional<double> sphere_t(DVec3 o, DVec3 d) {
  const DVec3 f = o - DVec3(0, kSphereHeight, 0);
  const double b = glm::dot(f, d), c = glm::dot(f, f) - 1.0;
  const double disc = b * b - c;
  if (disc < 0) return std::nullopt;
  const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
  if (t0 > 0) return t0;
  if (t1 > 0) return t1;
  return std::nullopt;
}

// Distance from the sphere's centre to the segment p -> light, minus the radius: > 0 lit.
double segment_clearance(DVec3 p) {
  const DVec3 c(0, kSphereHeight, 0);
  const DVec3 d = kLight - p;
  const double s = std::clamp(glm::dot(c - p, d) / glm::dot(d, d), 0.0, 1.0);
  return glm::length(p + s * d - c) - 1.0;
}

Vec3 to_float(DVec3 v) { return Vec3(v); }

}  // namespace

SceneDescription make_acne_scene(float scale, int width, int height) {
  const Placement place = placement(scale);
  SceneDescription scene;
  scene.source = "acne scene";
  scene.render.width = width;
  scene.render.height = height;
  scene.camera.position = to_float(place.to_world(kCameraPosition));
  scene.camera.look_at = to_float(place.to_world(kCameraTarget));
  scene.camera.up = to_float(place.rotation * DVec3(0, 1, 0));
  scene.camera.vfov_degrees = 45.0f;
  Material grey;
  grey.albedo = Color(0.7f);
  scene.materials = {grey};
  scene.shapes.push_back(Shape{"floor", Plane{to_float(place.to_world(DVec3(0))), to_float(place.rotation * DVec3(0, 1, 0))}, 0});
  scene.shapes.push_back(Shape{"ball", Sphere{to_float(place.to_world(DVec3(0, kSphereHeight, 0))), scale}, 0});
  scene.lights.push_back(PointLight{to_float(place.to_world(kLight)), Color(float(40.0 * double(scale) * double(scale)))});
  return scene;
}

ShadowErrors count_shadow_errors(float scale, const OffsetPolicy& policy, int width, int height) {
  const SceneDescription description = make_acne_scene(scale, width, height);
  const WhittedScene scene(description);
  const Camera camera(description.camera, width, height);
  const Placement place = placement(scale);
  const Vec3 light = description.lights[0].position;

  ShadowErrors errors;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = generate_camera_ray(camera, Vec2(float(x) + 0.5f, float(y) + 0.5f));
      const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
      if (!hit) continue;

      // The truth for the same float ray, in double, in the scene's own units.
      const DVec3 o = place.to_local(DVec3(ray.origin));
      const DVec3 d = glm::normalize(place.direction_to_local(DVec3(ray.direction)));
      const std::optional<double> t_sphere = sphere_t(o, d);
      const double t_plane = d.y != 0.0 ? -o.y / d.y : -1.0;
      const bool on_sphere = t_sphere.has_value() && (t_plane <= 0.0 || *t_sphere < t_plane);
      if (!on_sphere && t_plane <= 0.0) continue;
      if ((hit->primitive == 1) != on_sphere) continue;  // silhouette: the two disagree on the surface
      const DVec3 p = o + (on_sphere ? *t_sphere : t_plane) * d;

      double margin;  // how far the exact answer is from changing
      if (on_sphere) {
        const DVec3 n = p - DVec3(0, kSphereHeight, 0);
        margin = glm::dot(n, glm::normalize(kLight - p));  // cos at the terminator
      } else {
        margin = segment_clearance(p);
      }
      if (std::abs(margin) < kGuard) continue;
      const bool lit_truth = margin > 0.0;

      // The renderer's answer: light above the surface and the shadow ray unblocked.
      const Vec3 to_light = light - hit->point;
      bool lit = glm::dot(hit->normal, to_light) > 0.0f;
      if (lit) {
        const ShadowRay shadow = spawn_shadow_ray(*hit, light, policy);
        lit = !scene.occluded(shadow.ray, shadow.range);
      }
      ++errors.pixels;
      if (lit_truth && !lit) ++errors.acne;
      if (!lit_truth && lit) ++errors.leaks;
    }
  return errors;
}

}  // namespace rt
