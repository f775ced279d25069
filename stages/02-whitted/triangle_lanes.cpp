#include "02-whitted/triangle_lanes.h"

#include "common/task.h"

namespace rt {

std::optional<TriangleHit> intersect_triangle_lanes(const WatertightRay& ray, const LanesRay& lanes,
                                                    const TriangleCorners& triangle, Interval range) {
  // BEGIN TASK stage2.triangle.lanes
  const Float4 z = load4(triangle.coordinate[ray.kz]) - lanes.origin_z;
  const Float4 x = load4(triangle.coordinate[ray.kx]) - lanes.origin_x - lanes.shear_x * z;
  const Float4 y = load4(triangle.coordinate[ray.ky]) - lanes.origin_y - lanes.shear_y * z;
  // Lane 0: u = cx by - cy bx; lane 1: v = ax cy - ay cx; lane 2: w = bx ay - by ax.
  // Lane i takes its corner's two neighbours, i - 1 and i + 1 (mod 3).
  const Float4 x_prev = __builtin_shufflevector(x, x, 2, 0, 1, 3), y_prev = __builtin_shufflevector(y, y, 2, 0, 1, 3);
  const Float4 x_next = __builtin_shufflevector(x, x, 1, 2, 0, 3), y_next = __builtin_shufflevector(y, y, 1, 2, 0, 3);
  Float4 edge = x_prev * y_next - y_prev * x_next;
  if (lane_mask(edge == 0.0f) & 7u) {
    for (int i = 0; i < 3; ++i)
      edge[i] = float(double(x_prev[i]) * double(y_next[i]) - double(y_prev[i]) * double(x_next[i]));
  }
  const unsigned negative = lane_mask(edge < 0.0f) & 7u, positive = lane_mask(edge > 0.0f) & 7u;
  if ((negative != 0) & (positive != 0)) return std::nullopt;
  const float det = edge[0] + edge[1] + edge[2];
  if (det == 0.0f) return std::nullopt;

  const Float4 sheared_z = lanes.shear_z * z;
  const Float4 weighted = edge * sheared_z;
  const float inv_det = 1.0f / det;
  const float t = (weighted[0] + weighted[1] + weighted[2]) * inv_det;
  if (!range.surrounds(t)) return std::nullopt;
  const float max_z = max3(abs4(sheared_z));
  const float max_x = max3(abs4(x)), max_y = max3(abs4(y));
  const float max_edge = max3(abs4(edge));
  const float error_t = watertight_t_error_bound(max_x, max_y, max_z, max_edge, inv_det);
  if (!(t > error_t)) return std::nullopt;
  return TriangleHit{t, edge[1] * inv_det, edge[2] * inv_det};
  // PLACEHOLDER
  // report_unfinished_task("stage2.triangle.lanes");
  // (void)lanes;
  // return intersect_triangle_watertight(ray, triangle.corner(0), triangle.corner(1), triangle.corner(2), range);
  // END TASK
}

}  // namespace rt
