#include "01-ray-casting/disk_sampling.h"

#include "common/task.h"

#include <cmath>

namespace rt {

Vec2 sample_uniform_disk(Vec2 u) {
  // BEGIN TASK stage1.camera.concentric_disk
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return Vec2(0.0f);
  // The square [-1, 1]^2 is cut by its diagonals into four triangles; in each, the coordinate
  // with the larger magnitude is the radius r and the other sweeps the angle over a quarter turn:
  //   |a| > |b|: phi = (pi/4) (b/a),         (x, y) = r (cos phi, sin phi);
  //   else:      phi = pi/2 - (pi/4) (a/b),  (x, y) = r (sin theta, cos theta), theta = (pi/4) (a/b).
  // Both cases need the cosine and sine of theta in [-pi/4, pi/4] only, so they share one
  // computation, and the two come from a short polynomial (common/math.h) instead of a libm call
  // built for any angle. Which case applies is a coin toss for a random u, so the values are
  // picked by select() (common/math.h), with no jump that would be mispredicted half the time.
  const bool a_wins = std::abs(a) > std::abs(b);
  const float r = select(a_wins, a, b);
  const float theta = 0.25f * kPi * (select(a_wins, b, a) / r);
  const Vec2 cs = cos_sin_quarter_turn(theta);
  return r * Vec2(select(a_wins, cs.x, cs.y), select(a_wins, cs.y, cs.x));
  // PLACEHOLDER
  // report_unfinished_task("stage1.camera.concentric_disk");
  // (void)u;
  // return Vec2(0.0f);
  // END TASK
}

Vec2 invert_uniform_disk(Vec2 p) {
  const float r = glm::length(p);
  float a, b;
  if (std::abs(p.x) >= std::abs(p.y)) {
    a = p.x >= 0.0f ? r : -r;
    b = a == 0.0f ? 0.0f : a * std::atan(p.y / p.x) / (0.25f * kPi);
  } else {
    b = p.y >= 0.0f ? r : -r;
    const float phi = std::atan2(p.y / b, p.x / b);
    a = b * (0.5f * kPi - phi) / (0.25f * kPi);
  }
  return Vec2(0.5f * (a + 1.0f), 0.5f * (b + 1.0f));
}

}  // namespace rt
