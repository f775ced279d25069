#include "02-whitted/triangle_pack.h"

#include "common/task.h"

namespace rt {

std::optional<PackHit> intersect_triangle_pack(const WatertightRay& ray, const LanesRay& lanes,
                                               const TrianglePack& pack, Interval range) {
  // BEGIN TASK stage2.triangle.pack
  const Float4 a_z = load4(pack.corner[0][ray.kz]) - lanes.origin_z;
  const Float4 b_z = load4(pack.corner[1][ray.kz]) - lanes.origin_z;
  const Float4 c_z = load4(pack.corner[2][ray.kz]) - lanes.origin_z;
  const Float4 ax = load4(pack.corner[0][ray.kx]) - lanes.origin_x - lanes.shear_x * a_z;
  const Float4 ay = load4(pack.corner[0][ray.ky]) - lanes.origin_y - lanes.shear_y * a_z;
  const Float4 bx = load4(pack.corner[1][ray.kx]) - lanes.origin_x - lanes.shear_x * b_z;
  const Float4 by = load4(pack.corner[1][ray.ky]) - lanes.origin_y - lanes.shear_y * b_z;
  const Float4 cx = load4(pack.corner[2][ray.kx]) - lanes.origin_x - lanes.shear_x * c_z;
  const Float4 cy = load4(pack.corner[2][ray.ky]) - lanes.origin_y - lanes.shear_y * c_z;

  Float4 u = cx * by - cy * bx;
  Float4 v = ax * cy - ay * cx;
  Float4 w = bx * ay - by * ax;
  for (unsigned zero = lane_mask((u == 0.0f) | (v == 0.0f) | (w == 0.0f)); zero != 0; zero &= zero - 1) {
    const int i = __builtin_ctz(zero);
    u[i] = float(double(cx[i]) * double(by[i]) - double(cy[i]) * double(bx[i]));
    v[i] = float(double(ax[i]) * double(cy[i]) - double(ay[i]) * double(cx[i]));
    w[i] = float(double(bx[i]) * double(ay[i]) - double(by[i]) * double(ax[i]));
  }
  const Int4 mixed_signs = ((u < 0.0f) | (v < 0.0f) | (w < 0.0f)) & ((u > 0.0f) | (v > 0.0f) | (w > 0.0f));
  const Float4 det = u + v + w;
  Int4 valid = ~mixed_signs & (det != 0.0f);
  if (lane_mask(valid) == 0) return std::nullopt;  // the usual case in a leaf: four misses

  const Float4 az = lanes.shear_z * a_z, bz = lanes.shear_z * b_z, cz = lanes.shear_z * c_z;
  const Float4 inv_det = 1.0f / det;  // inf or NaN in the lanes already refused
  const Float4 t = (u * az + v * bz + w * cz) * inv_det;
  valid &= (range.min < t) & (t < range.max);
  const Float4 max_z = max4(max4(abs4(az), abs4(bz)), abs4(cz));
  const Float4 max_x = max4(max4(abs4(ax), abs4(bx)), abs4(cx));
  const Float4 max_y = max4(max4(abs4(ay), abs4(by)), abs4(cy));
  const Float4 max_edge = max4(max4(abs4(u), abs4(v)), abs4(w));
  valid &= t > watertight_t_error_bound(max_x, max_y, max_z, max_edge, inv_det);
  unsigned hits = lane_mask(valid);
  if (hits == 0) return std::nullopt;
  int nearest = __builtin_ctz(hits);
  for (hits &= hits - 1; hits != 0; hits &= hits - 1) {
    const int i = __builtin_ctz(hits);
    if (t[i] < t[nearest]) nearest = i;
  }
  return PackHit{t[nearest], v[nearest] * inv_det[nearest], w[nearest] * inv_det[nearest], nearest};
  // PLACEHOLDER
  // report_unfinished_task("stage2.triangle.pack");
  // (void)lanes;
  // std::optional<PackHit> nearest;
  // for (int lane = 0; lane < TrianglePack::kLanes; ++lane)
  //   if (const std::optional<TriangleHit> hit = intersect_triangle_watertight(
  //           ray, pack.vertex(lane, 0), pack.vertex(lane, 1), pack.vertex(lane, 2), range)) {
  //     nearest = PackHit{hit->t, hit->b1, hit->b2, lane};
  //     range.max = hit->t;
  //   }
  // return nearest;
  // END TASK
}

}  // namespace rt
