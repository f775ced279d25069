#include "common/camera.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace rt {
namespace {

TEST(CameraBasis, LookingDownPlusZHasPlusXOnTheLeft) {
  // docs/design.md: forward x up = right, so looking down +z with up +y, right is -x.
  const Camera camera(CameraSpec{Vec3(0), Vec3(0, 0, 1), Vec3(0, 1, 0), 90.0f}, 200, 100);
  EXPECT_EQ(camera.forward, Vec3(0, 0, 1));
  EXPECT_EQ(camera.right, Vec3(-1, 0, 0));
  EXPECT_EQ(camera.up, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(camera.aspect, 2.0f);
  EXPECT_NEAR(camera.tan_half_vfov, 1.0f, 1e-6f);
}

TEST(CameraBasis, TrueUpIsRecomputedFromATiltedUpVector) {
  const Camera camera(CameraSpec{Vec3(0), Vec3(0, 0, 1), Vec3(0, 1, 1), 40.0f}, 10, 10);
  EXPECT_NEAR(glm::dot(camera.up, camera.forward), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(camera.up), 1.0f, 1e-6f);
  EXPECT_GT(camera.up.y, 0.99f);
}

TEST(CameraBasis, RejectsSpecsWithoutAFrame) {
  EXPECT_THROW(Camera(CameraSpec{Vec3(1), Vec3(1), Vec3(0, 1, 0), 40.0f}, 10, 10),
               std::invalid_argument);
  EXPECT_THROW(Camera(CameraSpec{Vec3(0), Vec3(0, 5, 0), Vec3(0, 1, 0), 40.0f}, 10, 10),
               std::invalid_argument);
  EXPECT_THROW(Camera(CameraSpec{Vec3(0), Vec3(0, 0, 1), Vec3(0, 1, 0), 180.0f}, 10, 10),
               std::invalid_argument);
  EXPECT_THROW(Camera(CameraSpec{Vec3(0), Vec3(0, 0, 1), Vec3(0, 1, 0), 40.0f}, 0, 10),
               std::invalid_argument);
}

}  // namespace
}  // namespace rt
