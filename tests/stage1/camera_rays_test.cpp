#include "01-ray-casting/camera_rays.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::subject;

// Camera at the origin looking down +z, vfov 90 degrees (tan = 1), 200 x 100 pixels (aspect 2).
// Its right vector is -x (docs/design.md), so the LEFT edge of the image looks towards +x.
const Camera kCamera(CameraSpec{Vec3(0), Vec3(0, 0, 1), Vec3(0, 1, 0), 90.0f}, 200, 100);

void expect_direction(Vec2 film_point, Vec3 expected) {
  const Ray ray = subject([&] { return generate_camera_ray(kCamera, film_point); });
  EXPECT_EQ(ray.origin, Vec3(0));
  EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-6f);
  const Vec3 e = glm::normalize(expected);
  EXPECT_NEAR(ray.direction.x, e.x, 1e-6f) << "film point " << film_point.x << ", " << film_point.y;
  EXPECT_NEAR(ray.direction.y, e.y, 1e-6f) << "film point " << film_point.x << ", " << film_point.y;
  EXPECT_NEAR(ray.direction.z, e.z, 1e-6f) << "film point " << film_point.x << ", " << film_point.y;
}

TEST(CameraRays, ImageCentreLooksForward) { expect_direction({100, 50}, {0, 0, 1}); }

TEST(CameraRays, ImageCorners) {
  // Top-left corner: s_x = -aspect * tan = -2 along right = -x, s_y = +tan = +1 along up.
  expect_direction({0, 0}, {2, 1, 1});
  expect_direction({200, 0}, {-2, 1, 1});
  expect_direction({0, 100}, {2, -1, 1});
  expect_direction({200, 100}, {-2, -1, 1});
}

TEST(CameraRays, PixelCentres) {
  // Pixel (0, 0) covers [0,1) x [0,1); its centre is (0.5, 0.5):
  // s_x = (2 * 0.5 / 200 - 1) * 2 = -1.99, s_y = 1 - 2 * 0.5 / 100 = 0.99.
  expect_direction({0.5f, 0.5f}, {1.99f, 0.99f, 1.0f});
  // The last pixel (199, 99) mirrors it.
  expect_direction({199.5f, 99.5f}, {-1.99f, -0.99f, 1.0f});
}

TEST(CameraRays, FieldOfViewIsVertical) {
  // The ray through the top edge's midpoint is vfov/2 = 45 degrees above forward,
  // whatever the aspect ratio.
  const Ray top = subject([&] { return generate_camera_ray(kCamera, {100, 0}); });
  EXPECT_NEAR(std::acos(glm::dot(top.direction, Vec3(0, 0, 1))), radians(45.0f), 1e-6f);
  const Camera narrow(CameraSpec{Vec3(0), Vec3(0, 0, 1), Vec3(0, 1, 0), 30.0f}, 10, 500);
  const Ray narrow_top = subject([&] { return generate_camera_ray(narrow, {5, 0}); });
  EXPECT_NEAR(std::acos(glm::dot(narrow_top.direction, Vec3(0, 0, 1))), radians(15.0f), 1e-6f);
}

TEST(CameraRays, GeneralCameraFrame) {
  // Looking from (1, 2, 3) at the origin: the centre ray points at the origin.
  const Camera camera(CameraSpec{Vec3(1, 2, 3), Vec3(0), Vec3(0, 1, 0), 50.0f}, 64, 48);
  const Ray ray = subject([&] { return generate_camera_ray(camera, {32, 24}); });
  EXPECT_EQ(ray.origin, Vec3(1, 2, 3));
  EXPECT_NEAR(glm::length(ray.direction - glm::normalize(Vec3(-1, -2, -3))), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace rt
