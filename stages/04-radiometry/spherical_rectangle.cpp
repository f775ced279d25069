#include "04-radiometry/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace rt {

SphericalRectangle::SphericalRectangle(Vec3 x, Vec3 corner, Vec3 edge_u, Vec3 edge_v) : origin_(x) {
  const float width = glm::length(edge_u), height = glm::length(edge_v);
  axis_x_ = edge_u / width;
  axis_y_ = edge_v / height;
  axis_z_ = glm::cross(axis_x_, axis_y_);
  const Vec3 d = corner - x;
  x0_ = glm::dot(d, axis_x_);
  y0_ = glm::dot(d, axis_y_);
  z0_ = glm::dot(d, axis_z_);
  // The paper's frame has the rectangle below x (z0 < 0): flip the normal when it is above.
  if (z0_ > 0.0f) {
    z0_ = -z0_;
    axis_z_ = -axis_z_;
  }
  x1_ = x0_ + width;
  y1_ = y0_ + height;

  // The inner normals of the four great circles through the edges (v00 x v10, v10 x v11, v11 x v01,
  // v01 x v00 with vij = (xi, yj, z0)) reduce to two nonzero components each:
  //   n0 ~ (0, z0, -y0),  n1 ~ (-z0, 0, x1),  n2 ~ (0, -z0, y1),  n3 ~ (z0, 0, -x0).
  // Each interior angle is g = acos(-n_i . n_j) of two neighbouring normals.
  // In double: S is a difference of angles near 2 pi, so float would keep only ~2e-5 sr of it.
  const double z2 = double(z0_) * z0_, x0 = x0_, x1 = x1_, y0 = y0_, y1 = y1_;
  const double len_y0 = std::sqrt(z2 + y0 * y0), len_y1 = std::sqrt(z2 + y1 * y1);
  const double len_x0 = std::sqrt(z2 + x0 * x0), len_x1 = std::sqrt(z2 + x1 * x1);
  auto angle = [](double cosine) { return std::acos(std::clamp(cosine, -1.0, 1.0)); };
  const double g0 = angle(x1 * y0 / (len_x1 * len_y0));
  const double g1 = angle(-x1 * y1 / (len_x1 * len_y1));
  const double g2 = angle(x0 * y1 / (len_x0 * len_y1));
  const double g3 = angle(-x0 * y0 / (len_x0 * len_y0));
  b0_ = float(-y0 / len_y0);
  b1_ = float(y1 / len_y1);
  const double k = 2.0 * M_PI - g2 - g3;
  k_ = float(k);
  // Girard: the area of a spherical quadrilateral is its angle sum less 2 pi.
  solid_angle_ = float(std::max(0.0, g0 + g1 - k));
}

Vec3 SphericalRectangle::sample(Vec2 u) const {
  // Section 4.1: the column. au is the angle at which the part of the solid angle left of the
  // column is u S; the column's x follows from the cosine cu of the great circle through it.
  const float au = u.x * solid_angle_ + k_;
  const float fu = (std::cos(au) * b0_ - b1_) / std::sin(au);
  const float cu = std::clamp(std::copysign(1.0f, fu) / std::sqrt(fu * fu + b0_ * b0_), -1.0f, 1.0f);
  const float xu = std::clamp(-(cu * z0_) / std::sqrt(std::max(0.0f, 1.0f - cu * cu)), x0_, x1_);
  // Section 4.2: along the column, uniform in h = sin(elevation) between its ends.
  const float d = std::sqrt(xu * xu + z0_ * z0_);
  const float h0 = y0_ / std::sqrt(d * d + y0_ * y0_);
  const float h1 = y1_ / std::sqrt(d * d + y1_ * y1_);
  const float hv = h0 + u.y * (h1 - h0);
  const float hv2 = hv * hv;
  // At hv = +-1 (a column straight above x, d = 0) the formula divides by 0: the column's end.
  const float yv = hv2 < 1.0f - 1e-6f ? std::clamp(hv * d / std::sqrt(1.0f - hv2), y0_, y1_) : (hv > 0.0f ? y1_ : y0_);
  return origin_ + xu * axis_x_ + yv * axis_y_ + z0_ * axis_z_;
}

}  // namespace rt
