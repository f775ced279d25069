#include "common/frame.h"
#include "common/interval.h"
#include "common/hit.h"
#include "common/random.h"

#include <bit>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace rt {
namespace {

void expect_orthonormal_right_handed(const Frame& f) {
  EXPECT_NEAR(glm::length(f.s), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(f.s, f.t), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(f.s, f.n), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 1e-6f);
  const Vec3 c = glm::cross(f.s, f.t);
  EXPECT_NEAR(glm::length(c - f.n), 0.0f, 1e-5f) << "s x t must equal n (right-handed)";
}

TEST(Frame, OrthonormalAndRightHandedForManyNormals) {
  Rng rng(7, 0, 0);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 n = glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f);
    expect_orthonormal_right_handed(Frame::from_normal(n));
  }
}

TEST(Frame, PolesAndAxes) {
  // n.z = -1 is where naive constructions divide by zero.
  for (Vec3 n : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0),
                 glm::normalize(Vec3(1e-8f, 0, -1))})
    expect_orthonormal_right_handed(Frame::from_normal(n));
}

TEST(Frame, LocalWorldRoundTrip) {
  const Frame f = Frame::from_normal(glm::normalize(Vec3(0.3f, -0.5f, 0.8f)));
  const Vec3 v(0.2f, 0.7f, -0.4f);
  const Vec3 back = f.to_world(f.to_local(v));
  EXPECT_NEAR(glm::length(back - v), 0.0f, 1e-6f);
  EXPECT_NEAR(f.to_local(f.n).z, 1.0f, 1e-6f);
}

TEST(Interval, OpenAtBothEnds) {
  const Interval i{1.0f, 2.0f};
  EXPECT_FALSE(i.surrounds(1.0f));
  EXPECT_FALSE(i.surrounds(2.0f));
  EXPECT_TRUE(i.surrounds(1.5f));
  EXPECT_TRUE(i.contains(1.0f));
  EXPECT_FALSE(i.surrounds(std::nanf("")));
  EXPECT_FALSE(Interval::positive().surrounds(kInfinity));
  EXPECT_FALSE(Interval::positive().surrounds(0.0f));
  EXPECT_TRUE(Interval{}.is_empty());
}

TEST(Hit, FrontFaceRule) {
  Hit hit;
  const Ray towards_minus_z{Vec3(0, 0, 5), Vec3(0, 0, -1)};
  hit.set_face_normal(towards_minus_z, Vec3(0, 0, 1));
  EXPECT_TRUE(hit.front_face);
  EXPECT_EQ(hit.normal, Vec3(0, 0, 1));
  hit.set_face_normal(towards_minus_z, Vec3(0, 0, -1));  // hitting the back side
  EXPECT_FALSE(hit.front_face);
  EXPECT_EQ(hit.normal, Vec3(0, 0, 1)) << "the normal must face the incoming ray";
}

TEST(NextFloat, MatchesNextafterEverywhereButNan) {
  // Bit for bit (signed zeros included) against the library, at the awkward values and at a
  // million random bit patterns of every exponent.
  auto same = [](float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); };
  const float denorm = std::numeric_limits<float>::denorm_min(), big = std::numeric_limits<float>::max();
  std::vector<float> values{0.0f, -0.0f, denorm, -denorm, 1.0f, -1.0f, big, -big, kInfinity, -kInfinity,
                            std::numeric_limits<float>::min(), -std::numeric_limits<float>::min()};
  Rng rng(5, 0, 0);
  while (values.size() < 1000000) {
    const float v = std::bit_cast<float>(rng.next_u32());
    if (!std::isnan(v)) values.push_back(v);
  }
  for (const float v : values) {
    ASSERT_TRUE(same(next_float_up(v), std::nextafter(v, kInfinity))) << v;
    ASSERT_TRUE(same(next_float_down(v), std::nextafter(v, -kInfinity))) << v;
  }
}

TEST(CosSinQuarterTurn, WithinAnUlpOfTheLibraryOverItsRange) {
  // Both within 2^-23 (one ulp just below 1, two below 0.5) of the double-precision values at
  // 100,001 angles over [-pi/4, pi/4]: a wrong or missing term of either series (the smallest one
  // kept, theta^9 / 9!, is worth 3e-7 at the ends) is far outside.
  double worst = 0.0;
  for (int i = -50000; i <= 50000; ++i) {
    const float theta = float(i) / 50000.0f * (0.25f * kPi);
    const Vec2 cs = cos_sin_quarter_turn(theta);
    worst = std::max({worst, std::abs(double(cs.x) - std::cos(double(theta))),
                      std::abs(double(cs.y) - std::sin(double(theta)))});
  }
  EXPECT_LE(worst, 0x1p-23) << "largest error " << worst;
}

TEST(Select, ReturnsTheChosenValueBitForBit) {
  // Either value whole, whatever its bits: signed zeros, infinities, NaNs with a payload.
  auto bits = [](float v) { return std::bit_cast<std::uint32_t>(v); };
  const float nan = std::bit_cast<float>(0x7fc01234u);
  const float values[] = {0.0f, -0.0f, 1.5f, -2.25f, kInfinity, -kInfinity, nan, std::numeric_limits<float>::denorm_min()};
  for (const float a : values)
    for (const float b : values) {
      EXPECT_EQ(bits(select(true, a, b)), bits(a));
      EXPECT_EQ(bits(select(false, a, b)), bits(b));
    }
}

}  // namespace
}  // namespace rt
