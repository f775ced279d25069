// Stage 4, beyond the lecture: sampling a rectangle by the solid angle it subtends. Area sampling
// (the lecture's method) draws points uniformly over the rectangle, so a direction's density
// p_w = |x - y|^2 / (A cos(theta_y)) varies with the distance and the tilt of each point: near a
// large light the estimate f Le cos / p_w swings with them. Sampling uniformly over the spherical
// rectangle, the rectangle's projection onto the unit sphere around x, makes p_w = 1 / S constant,
// and only f and cos(theta_x) vary.
//
// Urena, Fajardo & King, "An Area-Preserving Parametrization for Spherical Rectangles", EGSR 2013.
// In a frame with x at the origin, the rectangle's axes along x and y and its plane at z = z0 < 0,
// the rectangle is [x0, x1] x [y0, y1]. Its spherical rectangle is bounded by four great circles,
// one through each edge; their inner normals n0..n3 and the interior angles g0..g3 between them
// give the solid angle by Girard's theorem, S = g0 + g1 + g2 + g3 - 2 pi (section 3). A sample
// (u, v) first picks the x coordinate so that the part of the solid angle left of it is u S
// (section 4.1, inverting the area of a spherical quadrilateral), then y along that column
// uniformly in the sine of its elevation, which is uniform in solid angle (section 4.2).
#pragma once

#include "common/math.h"

namespace rt {

class SphericalRectangle {
 public:
  // The rectangle corner + s edge_u + t edge_v, (s, t) in [0, 1]^2, seen from x. The edges must be
  // perpendicular; x must not lie in the rectangle's plane (then the solid angle is 0).
  SphericalRectangle(Vec3 x, Vec3 corner, Vec3 edge_u, Vec3 edge_v);

  // S, in steradians.
  float solid_angle() const { return solid_angle_; }
  // The point on the rectangle whose direction from x is uniform in solid angle (density 1 / S),
  // for u in [0, 1)^2. Neighbouring (u, v) give neighbouring points, so stratified u stay stratified.
  Vec3 sample(Vec2 u) const;

 private:
  Vec3 origin_;                 // x
  Vec3 axis_x_, axis_y_, axis_z_;  // the local frame: unit edges and the normal pointing away from the plane
  float x0_, x1_, y0_, y1_, z0_;   // the rectangle in that frame, z0 <= 0
  float b0_, b1_;                  // the z components of n0 and n2
  float k_;                        // 2 pi - g2 - g3
  float solid_angle_;
};

}  // namespace rt
