// Stage 1, task stage1.camera.concentric_disk: a uniform point on the unit disk, for the thin lens
// (camera_rays.h). Stage 4 reuses it for cosine-weighted directions (Malley's method), so the map,
// its density and its inverse sit together, as every warp of stage 4 does (04-radiometry/warp.h).
#pragma once

#include "common/math.h"

namespace rt {

// Uniform over the unit disk by Shirley and Chiu's concentric map ("A Low Distortion Map Between
// Disk and Square", JGT 2(3), 1997): the square's concentric squares go to the disk's concentric
// circles, so strata stay compact. pdf = 1 / pi per unit area.
Vec2 sample_uniform_disk(Vec2 u);
inline float uniform_disk_pdf(Vec2 p) { return p.x * p.x + p.y * p.y <= 1.0f ? kInvPi : 0.0f; }

// The u that sample_uniform_disk maps to p (a point on the disk): in the sector |x| >= |y| the
// radius was a = 2 u0 - 1 and y / x = tan(pi/4 b / a); in the other, b = 2 u1 - 1 and the angle
// pi/2 - pi/4 a / b.
Vec2 invert_uniform_disk(Vec2 p);

}  // namespace rt
