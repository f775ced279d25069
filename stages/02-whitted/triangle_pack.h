// Stage 2, beyond the lecture: four triangles tested at once, one per SIMD lane. Where
// triangle_lanes.h puts one triangle's three corners in the lanes, here each lane is a whole
// triangle, and every line of the watertight test is one instruction for four triangles: stage 3's
// BVH stores the triangles of a leaf this way (a "pack"), so that a leaf costs one test instead of
// one per triangle. Packing primitives for SIMD: Wald, Benthin & Boulos, "Getting Rid of Packets",
// IRT 2008 (Embree's Triangle4 works the same way).
//
// Lane by lane the arithmetic is the scalar watertight test's (triangle_intersection.h), in its
// order, so each lane answers what the scalar test answers for its triangle, bit for bit
// (tests/stage2/triangle_pack_test.cpp).
#pragma once

#include "02-whitted/triangle_lanes.h"

#include <cstdint>
#include <cstring>
#include <span>

namespace rt {

// Up to four triangles stored corner by corner, then axis by axis: corner[c][axis][lane], so that
// a row of four lanes is one load and the ray's permuted axes kx, ky, kz pick rows. 144 bytes. A
// pack of fewer than four repeats its first triangle in the unused lanes: their hits can only tie
// with lane 0's, and a tie goes to the lowest lane.
struct alignas(16) TrianglePack {
  static constexpr int kLanes = 4;
  float corner[3][3][kLanes];

  TrianglePack() = default;
  // One to four triangles (a leaf's).
  explicit TrianglePack(std::span<const TriangleCorners> triangles) {
    for (int lane = 0; lane < kLanes; ++lane) {
      const TriangleCorners& triangle = triangles[lane < int(triangles.size()) ? size_t(lane) : 0];
      for (int c = 0; c < 3; ++c)
        for (int axis = 0; axis < 3; ++axis) corner[c][axis][lane] = triangle.coordinate[axis][c];
    }
  }
  Vec3 vertex(int lane, int c) const { return Vec3(corner[c][0][lane], corner[c][1][lane], corner[c][2][lane]); }

  // The pack gathered from a mesh's vertices: lane i's corner c is base[corner[c][i]]. Always
  // inlined: stage 3's compact leaves (BvhBuildOptions::compact_packs) gather a pack at every test,
  // and its rows then go from registers to the test. Four scalar loads per row: loaded whole and
  // transposed in SSE registers, the corners went through the stack in a loop (docs/stage3.md,
  // ladder step 12).
  [[gnu::always_inline]] static TrianglePack gather(const Vec3* base, const std::uint16_t (&corner)[3][kLanes]) {
    TrianglePack pack;
    for (int c = 0; c < 3; ++c) {
      const float* p[kLanes];
      for (int lane = 0; lane < kLanes; ++lane) p[lane] = &base[corner[c][lane]].x;
      for (int axis = 0; axis < 3; ++axis) {
        const Float4 row{p[0][axis], p[1][axis], p[2][axis], p[3][axis]};
        std::memcpy(pack.corner[c][axis], &row, sizeof row);
      }
    }
    return pack;
  }
};
static_assert(sizeof(TrianglePack) == 144, "a pack is 36 floats");

// The nearest hit in a pack, and which lane holds its triangle.
struct PackHit {
  float t, b1, b2;
  int lane;
};

// Task stage2.triangle.pack. The nearest hit with t strictly inside `range` among the pack's four
// triangles, each tested as intersect_triangle_watertight tests it for the same prepared ray (`ray`,
// and `lanes` made from it), bit for bit; on equal t the lowest lane, as testing the lanes one after
// another with a shrinking range would answer. Lane i of each register holds triangle i.
//   1. Rows kz, kx, ky of each corner (load4), minus the origin's coordinate, and the shear:
//      x' = x - shear_x z, y' = y - shear_y z.
//   2. The edge functions U, V, W of all four triangles, each one line; a lane where any is exactly
//      0 recomputes its three in double, as the scalar test does.
//   3. The lanes' verdicts as masks (a comparison of Float4s is one): inside (no mixed signs),
//      det = (U + V) + W not 0, t inside the range and above its error bound
//      (watertight_t_error_bound, on Float4s); then the nearest lane of the mask.
std::optional<PackHit> intersect_triangle_pack(const WatertightRay& ray, const LanesRay& lanes,
                                               const TrianglePack& pack, Interval range);

}  // namespace rt
