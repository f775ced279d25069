// Stage 3, beyond the lecture: the end of its speed ladder (docs/stage3.md, section 5). The binary
// BVH collapsed into the 4-wide tree (wide_bvh.h), and each leaf of one to four triangles stored
// as a triangle pack, whose four triangles one SIMD test intersects (stage 2's triangle_pack.h):
// copied (160 bytes) or compact (48 bytes: the mesh, its triangles and their corners' vertex
// numbers; the corners read from the mesh at each test). Any other leaf keeps its primitives in
// slots. The lecture's BvhAggregate becomes this when built with BvhBuildOptions::wide.
#pragma once

#include "02-whitted/triangle_kind.h"
#include "02-whitted/triangle_pack.h"
#include "03-acceleration/bvh_build.h"
#include "03-acceleration/flat_primitives.h"
#include "03-acceleration/wide_bvh.h"
#include "common/parallel.h"

#include <algorithm>
#include <array>
#include <span>

namespace rt {

template <class Set>
class PackedWideBvh {
 public:
  // From the binary tree built over the set, whose leaves and leaf order it takes (it keeps neither).
  PackedWideBvh(std::shared_ptr<const Set> primitives, const Bvh& binary, const BvhBuildOptions& options);
  // The Aggregate contract (stage 2's aggregate.h) for a ray and its prepared form.
  [[gnu::always_inline]] std::optional<PrimitiveHit> closest_hit(const Ray& ray, const TriangleRay& prepared,
                                                                 Interval range) const;
  bool occluded(const Ray& ray, const TriangleRay& prepared, Interval range) const;

  const WideBvh& tree() const { return tree_; }
  // The leaves stored as packs, copied or compact (BvhBuildOptions::compact_packs).
  size_t packs() const { return packs_.size() + compact_packs_.size(); }
  // Memory: nodes, packs and the slots' copied primitives.
  size_t bytes() const {
    return tree_.nodes.size() * sizeof(WideBvhNode) + packs_.size() * (sizeof(TrianglePack) + sizeof(PackTriangles)) +
           compact_packs_.size() * sizeof(CompactPack) + slots_.bytes();
  }

  // A leaf whose count has this bit set is a pack: child is the pack's index.
  static constexpr std::uint32_t kPackedLeaf = 1u << 31;

 private:
  static_assert(BvhBuildOptions::kPackSize == TrianglePack::kLanes, "the builder prices the packs this tree makes");
  // TriangleKind's place in the set; kKinds when the set has no triangles (and so no packs).
  static constexpr size_t kTriangles = [] {
    if constexpr (Set::template contains<TriangleKind>())
      return Set::template index_of<TriangleKind>();
    else
      return Set::kKinds;
  }();
  // Which triangle each lane of a pack holds: its index in the triangle kind's store.
  using PackTriangles = std::array<std::uint32_t, TrianglePack::kLanes>;
  // A pack stored compactly (BvhBuildOptions::compact_packs): its triangles' mesh, each lane's
  // triangle in that mesh, and each lane's corners as vertex numbers: corner[c][lane] above the
  // pack's lowest, `base`. The corners' numbers are in the pack itself, so a test reads the pack
  // and then the corners: one dependent read fewer than through the mesh's triangle list, which at
  // 10^6 triangles halved the time per ray (docs/stage3.md, ladder step 12). 48 bytes.
  struct CompactPack {
    std::uint32_t mesh, base;
    PackTriangles triangle;
    std::uint16_t corner[3][TrianglePack::kLanes];
  };
  static_assert(sizeof(CompactPack) == 48);
  // The widest spread of vertex numbers a compact pack can hold; a leaf whose corners spread wider
  // keeps its slots.
  static constexpr std::uint32_t kCompactSpread = 0xffff;
  // The nearest hit in the pack of a packed leaf, its corners read from the copy or the mesh. The
  // layout is a template argument, chosen once per query (docs/stage3.md, section 5).
  template <bool kCompact>
  [[gnu::always_inline]] std::optional<PackHit> intersect_pack(std::uint32_t child, const TriangleRay& ray,
                                                               Interval range) const {
    if constexpr (!kCompact) return intersect_triangle_pack(ray.watertight, ray.lanes, packs_[child], range);
    const CompactPack& pack = compact_packs_[child];
    const Vec3* corners = triangles_->meshes[pack.mesh].geometry.positions.data() + pack.base;
    return intersect_triangle_pack(ray.watertight, ray.lanes, TrianglePack::gather(corners, pack.corner), range);
  }
  // The triangle kind's number of the triangle in a pack's lane.
  std::uint32_t pack_triangle(std::uint32_t child, int lane) const {
    if (!compact_) return pack_triangles_[child][size_t(lane)];
    const CompactPack& pack = compact_packs_[child];
    return triangles_->first[pack.mesh] + pack.triangle[size_t(lane)];
  }
  // The lowest and highest vertex number among the corners of the given triangles of one mesh.
  template <class Triangles>
  static std::pair<std::uint32_t, std::uint32_t> vertex_span(const std::vector<std::array<std::uint32_t, 3>>& mesh,
                                                             const Triangles& triangles) {
    std::pair<std::uint32_t, std::uint32_t> span{~0u, 0u};
    for (const std::uint32_t t : triangles)
      for (const std::uint32_t v : mesh[t]) span = {std::min(span.first, v), std::max(span.second, v)};
    return span;
  }
  // Whether a leaf of triangles (set numbers; the kind's first is `first_triangle`) can be a compact
  // pack: all of one mesh, their corners' vertex numbers within kCompactSpread of each other.
  bool fits_compact_pack(std::span<const std::uint32_t> leaf, std::uint32_t first_triangle) const {
    const std::uint32_t mesh = triangles_->mesh_of[leaf[0] - first_triangle];
    PackTriangles in_mesh{};  // the leaf's triangles numbered in their mesh
    for (size_t i = 0; i < leaf.size(); ++i) {
      if (triangles_->mesh_of[leaf[i] - first_triangle] != mesh) return false;
      in_mesh[i] = leaf[i] - first_triangle - triangles_->first[mesh];
    }
    const auto [low, high] =
        vertex_span(triangles_->meshes[mesh].geometry.triangles, std::span(in_mesh.data(), leaf.size()));
    return high - low <= kCompactSpread;
  }

  WideBvh tree_;
  FlatPrimitives<Set> slots_;  // the leaves that are not packs
  std::vector<TrianglePack, CacheLineAllocator<TrianglePack>> packs_;
  std::vector<PackTriangles, CacheLineAllocator<PackTriangles>> pack_triangles_;
  bool compact_ = false;  // the packs are compact_packs_, not packs_
  std::vector<CompactPack, CacheLineAllocator<CompactPack>> compact_packs_;
  const TriangleKind::Store* triangles_ = nullptr;  // what compact packs name (the set, kept alive by slots_)
};

template <class Set>
PackedWideBvh<Set>::PackedWideBvh(std::shared_ptr<const Set> primitives, const Bvh& binary,
                                  const BvhBuildOptions& options)
    : tree_(collapse_to_wide(binary)) {
  // A leaf becomes a pack when it holds one to four triangles (for a compact pack, of one mesh and
  // within kCompactSpread vertex numbers) and the scene's triangle test is the watertight one,
  // whose answers the pack's test gives bit for bit; any other leaf keeps its primitives in slots,
  // copied out in leaf order.
  const std::array<std::uint32_t, Set::kKinds + 1> first = first_of_each_kind(*primitives);
  bool may_pack = false;
  if constexpr (kTriangles < Set::kKinds) {
    may_pack =
        options.triangle_packs && primitives->template store<kTriangles>().method != TriangleMethod::moller_trumbore;
    compact_ = may_pack && options.compact_packs;
    triangles_ = &primitives->template store<kTriangles>();
  }
  std::vector<std::uint32_t> loose;  // the set numbers of the slots' primitives, in leaf order
  // First, in node order, which leaves become packs (numbered in that order): each pack's leaf, as
  // its first entry in the leaf order and its count.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> packed_leaves;
  if (may_pack) packed_leaves.reserve(binary.nodes.size() / 2 + 1);  // a binary tree of n nodes has (n + 1) / 2 leaves
  for (WideBvhNode& node : tree_.nodes)
    for (int i = 0; i < WideBvhNode::kWidth; ++i) {
      if (node.count[i] == 0) continue;
      const std::span<const std::uint32_t> leaf(binary.order.data() + node.child[i], node.count[i]);
      if constexpr (kTriangles < Set::kKinds) {
        const auto is_triangle = [&](std::uint32_t n) { return n >= first[kTriangles] && n < first[kTriangles + 1]; };
        if (may_pack && leaf.size() <= size_t(TrianglePack::kLanes) && std::ranges::all_of(leaf, is_triangle) &&
            (!compact_ || fits_compact_pack(leaf, first[kTriangles]))) {
          packed_leaves.emplace_back(node.child[i], node.count[i]);
          node.child[i] = std::uint32_t(packed_leaves.size() - 1);
          node.count[i] |= kPackedLeaf;
          continue;
        }
      }
      node.child[i] = std::uint32_t(loose.size());
      loose.insert(loose.end(), leaf.begin(), leaf.end());
    }
  // Then the packs, on every build thread: copying a triangle's corners, a thread spends most of
  // its time waiting for memory, as they are far from the last one's.
  if constexpr (kTriangles < Set::kKinds) {
    const TriangleKind::Store& store = primitives->template store<kTriangles>();
    if (compact_) {
      compact_packs_.resize(packed_leaves.size());
    } else {
      packs_.resize(packed_leaves.size());
      pack_triangles_.resize(packed_leaves.size());
    }
    for_each_chunk(packed_leaves.size(), options.build_threads, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) {
        const auto [at, count] = packed_leaves[k];
        PackTriangles triangle;  // a pack of fewer than four repeats its first triangle
        for (size_t lane = 0; lane < TrianglePack::kLanes; ++lane)
          triangle[lane] = binary.order[at + (lane < count ? lane : 0)] - first[kTriangles];
        if (compact_) {
          CompactPack& pack = compact_packs_[k];
          pack.mesh = store.mesh_of[triangle[0]];
          const auto& mesh_triangles = store.meshes[pack.mesh].geometry.triangles;
          for (size_t lane = 0; lane < TrianglePack::kLanes; ++lane) triangle[lane] -= store.first[pack.mesh];
          pack.triangle = triangle;
          pack.base = vertex_span(mesh_triangles, triangle).first;
          for (size_t lane = 0; lane < TrianglePack::kLanes; ++lane)
            for (size_t c = 0; c < 3; ++c)
              pack.corner[c][lane] = std::uint16_t(mesh_triangles[triangle[lane]][c] - pack.base);
          continue;
        }
        std::array<TriangleCorners, TrianglePack::kLanes> corners;
        for (size_t lane = 0; lane < TrianglePack::kLanes; ++lane)
          corners[lane] = TriangleKind::hot(store, triangle[lane]);
        pack_triangles_[k] = triangle;
        packs_[k] = TrianglePack(std::span<const TriangleCorners>(corners.data(), count));
      }
    });
  }
  slots_ = FlatPrimitives<Set>(std::move(primitives), loose);
}

template <class Set>
inline std::optional<PrimitiveHit> PackedWideBvh<Set>::closest_hit(const Ray& ray, const TriangleRay& prepared,
                                                                   Interval range) const {
  // The nearest hit's t, b1, b2 field by field (FlatPrimitives::hit_distance), and where it is: its
  // slot, or its pack and lane (4 pack + lane) when packed.
  float b1 = 0.0f, b2 = 0.0f;
  auto hit_primitive = [&](std::uint32_t slot, Interval r) { return slots_.hit_distance(slot, prepared, r, b1, b2); };
  std::uint32_t where = 0;
  bool in_pack = false;
  auto hit_slots = slot_by_slot(hit_primitive, where);
  auto search = [&](auto compact) __attribute__((always_inline)) {
    auto hit_leaf = [&](std::uint32_t child, std::uint32_t count, Interval r) __attribute__((always_inline))
                        ->std::optional<float> {
      if (count & kPackedLeaf) {
        const std::optional<PackHit> hit = intersect_pack<decltype(compact)::value>(child, prepared, r);
        if (!hit) return std::nullopt;
        b1 = hit->b1;
        b2 = hit->b2;
        where = child * TrianglePack::kLanes + std::uint32_t(hit->lane);
        in_pack = true;
        return hit->t;
      }
      const std::optional<float> t = hit_slots(child, count, r);
      if (t) in_pack = false;
      return t;
    };
    return wide_bvh_closest_hit(tree_, ray, range, hit_leaf);
  };
  // The default layout is the straight path (docs/stage3.md, section 5).
  std::optional<float> t;
  if (compact_) [[unlikely]]
    t = search(std::true_type{});
  else
    t = search(std::false_type{});
  if (!t) return std::nullopt;
  PrimitiveHit nearest{*t, b1, b2};
  if (in_pack) {
    nearest.kind = std::uint8_t(kTriangles);
    nearest.index = pack_triangle(where / TrianglePack::kLanes, int(where % TrianglePack::kLanes));
  } else {
    slots_.name(nearest, where);
  }
  return nearest;
}

template <class Set>
bool PackedWideBvh<Set>::occluded(const Ray& ray, const TriangleRay& prepared, Interval range) const {
  auto search = [&](auto compact) {
    auto hits_leaf = [&](std::uint32_t child, std::uint32_t count, Interval r) __attribute__((always_inline)) {
      if (count & kPackedLeaf) return intersect_pack<decltype(compact)::value>(child, prepared, r).has_value();
      for (std::uint32_t slot = child; slot < child + count; ++slot)
        if (slots_.occludes(slot, prepared, r)) return true;
      return false;
    };
    return wide_bvh_any_hit(tree_, ray, range, hits_leaf);
  };
  return compact_ ? search(std::true_type{}) : search(std::false_type{});
}

}  // namespace rt
