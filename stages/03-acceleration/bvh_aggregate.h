// Stage 3: the two aggregates stage 3 compares, behind stage 2's Aggregate interface: the naive one
// (every primitive against every ray: the correctness oracle and the baseline) and the BVH, over
// every kind of primitive of a set together.
#pragma once

#include "02-whitted/aggregate.h"
#include "02-whitted/triangle_kind.h"
#include "03-acceleration/bvh.h"
#include "03-acceleration/wide_bvh.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <span>

namespace rt {

// The primitives of every kind as one list of slots, each holding what its kind's test reads (its
// hot data: a triangle's corners, a sphere) and which primitive it is, in a given order: a BVH's
// leaf order, so that the primitives of a leaf sit next to each other in memory. A slot's
// test is a direct call of its kind's (visit_kind), not a virtual one.
template <class Set>
class FlatPrimitives {
 public:
  FlatPrimitives() = default;
  // Every primitive, in the set's own numbering (kind by kind, as bounds_in_set_order lists them).
  explicit FlatPrimitives(std::shared_ptr<const Set> set);
  // Slot s holds the primitive numbered numbers[s] in the set's own numbering.
  FlatPrimitives(std::shared_ptr<const Set> set, std::span<const std::uint32_t> numbers);
  // Every primitive's box in the set's own numbering: what a BVH is built from.
  static std::vector<Aabb, CacheLineAllocator<Aabb>> bounds_in_set_order(const Set& set);
  size_t size() const { return hot_.size(); }
  // The hit of the primitive in `slot` with t strictly inside `range`.
  std::optional<PrimitiveHit> intersect(size_t slot, const TriangleRay& ray, Interval range) const {
    std::optional<PrimitiveHit> hit = test(slot, ray, range);
    if (hit) name(*hit, slot);
    return hit;
  }
  // Fills in which primitive the hit in `slot` is (its kind and index).
  void name(PrimitiveHit& hit, size_t slot) const {
    hit.kind = std::uint8_t(hot_[slot].index());
    hit.index = index_[slot];
  }
  // Whether that primitive is hit at all: the shadow rays' question, which reads no index.
  bool occludes(size_t slot, const TriangleRay& ray, Interval range) const {
    return test(slot, ray, range).has_value();
  }
  size_t bytes() const { return size() * (sizeof(hot_[0]) + sizeof(index_[0])); }

  // The slot's kind's own test: t, b1, b2 of its hit (kind and index left unset).
  std::optional<PrimitiveHit> test(size_t slot, const TriangleRay& ray, Interval range) const {
    const typename Set::AnyHot& hot = hot_[slot];
    return visit_kind<Set::kKinds>(hot.index(), [&](auto k) {
      return Set::template Kind<k>::intersect(set_->template store<k>(), *std::get_if<k>(&hot), ray, range);
    });
  }

 private:
  std::shared_ptr<const Set> set_;
  // Per slot (in huge pages when large: CacheLineAllocator).
  std::vector<typename Set::AnyHot, CacheLineAllocator<typename Set::AnyHot>> hot_;
  std::vector<std::uint32_t, CacheLineAllocator<std::uint32_t>> index_;  // the primitive's index within its kind
};

template <class Set>
class NaiveAggregate : public Aggregate {
 public:
  explicit NaiveAggregate(std::shared_ptr<const Set> primitives) : flat_(std::move(primitives)) {}
  std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const override;
  bool occluded(const Ray& ray, Interval range) const override;

 private:
  FlatPrimitives<Set> flat_;
};
template <class Set>
NaiveAggregate(std::shared_ptr<Set>) -> NaiveAggregate<std::remove_const_t<Set>>;

template <class Set>
class BvhAggregate : public Aggregate {
 public:
  BvhAggregate(std::shared_ptr<const Set> primitives, const BvhBuildOptions& options);
  std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const override;
  bool occluded(const Ray& ray, Interval range) const override;

  // The binary tree; empty once collapsed into the 4-wide one, which is then all the traversal reads.
  const Bvh& bvh() const { return bvh_; }
  const std::optional<WideBvh>& wide_bvh() const { return wide_; }
  // The binary tree's figures, taken before a collapse released it.
  const BvhStats& stats() const { return stats_; }
  size_t size() const { return primitives_; }
  // The 4-wide tree's leaves stored as triangle packs (BvhBuildOptions::triangle_packs), copied
  // or compact (BvhBuildOptions::compact_packs).
  size_t packs() const { return packs_.size() + compact_packs_.size(); }
  // Memory of the acceleration structure: nodes, leaf order, packs and the slots' copied primitives.
  size_t bytes() const {
    return bvh_.nodes.size() * sizeof(BvhNode) + (wide_ ? wide_->nodes.size() * sizeof(WideBvhNode) : 0) +
           bvh_.order.size() * sizeof(std::uint32_t) + packs_.size() * (sizeof(TrianglePack) + sizeof(PackTriangles)) +
           compact_packs_.size() * sizeof(CompactPack) + flat_.bytes();
  }

  // A leaf of the 4-wide tree whose count has this bit set is a pack: child is the pack's index.
  static constexpr std::uint32_t kPackedLeaf = 1u << 31;

 private:
  static_assert(BvhBuildOptions::kPackSize == TrianglePack::kLanes, "the builder prices the packs this aggregate makes");
  // TriangleKind's place in the set; kKinds when the set has no triangles (and so no packs).
  static constexpr size_t kTriangles = [] {
    if constexpr (Set::template contains<TriangleKind>()) return Set::template index_of<TriangleKind>();
    else return Set::kKinds;
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
  // layout is a template argument, chosen once per query, not once per pack (0.8 % more
  // instructions per path on the Cornell box, callgrind).
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
  // Stores the 4-wide tree's leaves: as triangle packs where they can be, the rest in flat_.
  void store_wide_leaves(std::shared_ptr<const Set> primitives, const BvhBuildOptions& options);

  size_t primitives_ = 0;
  FlatPrimitives<Set> flat_;  // the binary tree's leaves; the 4-wide tree's leaves that are not packs
  Bvh bvh_;
  BvhStats stats_;
  std::optional<WideBvh> wide_;  // when built with BvhBuildOptions::wide
  std::vector<TrianglePack, CacheLineAllocator<TrianglePack>> packs_;
  std::vector<PackTriangles, CacheLineAllocator<PackTriangles>> pack_triangles_;
  bool compact_ = false;  // the packs are compact_packs_, not packs_
  std::vector<CompactPack, CacheLineAllocator<CompactPack>> compact_packs_;
  const TriangleKind::Store* triangles_ = nullptr;  // what compact packs name (the set, kept alive by flat_)
};
template <class Set>
BvhAggregate(std::shared_ptr<Set>, const BvhBuildOptions&) -> BvhAggregate<std::remove_const_t<Set>>;

// For the scenes: `--accel naive|median|middle|sah`.
template <class Set>
AggregateFactory<Set> naive_aggregate_factory() {
  return [](std::shared_ptr<const Set> p) { return std::make_unique<NaiveAggregate<Set>>(std::move(p)); };
}
template <class Set>
AggregateFactory<Set> bvh_aggregate_factory(const BvhBuildOptions& options) {
  return [options](std::shared_ptr<const Set> p) { return std::make_unique<BvhAggregate<Set>>(std::move(p), options); };
}

// first[k]: the number of kind k's first primitive in the set's numbering; first[kKinds] is the
// number of primitives.
template <class Set>
std::array<std::uint32_t, Set::kKinds + 1> first_of_each_kind(const Set& set) {
  std::array<std::uint32_t, Set::kKinds + 1> first{};
  Set::for_each_kind([&](auto k) {
    first[k + 1] = first[k] + std::uint32_t(Set::template Kind<k>::size(set.template store<k>()));
  });
  return first;
}

inline std::vector<std::uint32_t> numbers_up_to(size_t count) {
  std::vector<std::uint32_t> numbers(count);
  std::iota(numbers.begin(), numbers.end(), 0u);
  return numbers;
}

template <class Set>
FlatPrimitives<Set>::FlatPrimitives(std::shared_ptr<const Set> set)
    : FlatPrimitives(set, numbers_up_to(set->size())) {}

template <class Set>
FlatPrimitives<Set>::FlatPrimitives(std::shared_ptr<const Set> set, std::span<const std::uint32_t> numbers)
    : set_(std::move(set)) {
  const std::array<std::uint32_t, Set::kKinds + 1> first = first_of_each_kind(*set_);
  hot_.reserve(numbers.size());
  index_.reserve(numbers.size());
  for (const std::uint32_t number : numbers) {
    size_t kind = 0;
    while (number >= first[kind + 1]) ++kind;
    const std::uint32_t i = number - first[kind];
    visit_kind<Set::kKinds>(kind, [&](auto k) {
      hot_.emplace_back(std::in_place_index<k>, Set::template Kind<k>::hot(set_->template store<k>(), i));
    });
    index_.push_back(i);
  }
}

template <class Set>
std::vector<Aabb, CacheLineAllocator<Aabb>> FlatPrimitives<Set>::bounds_in_set_order(const Set& set) {
  std::vector<Aabb, CacheLineAllocator<Aabb>> bounds;
  bounds.reserve(set.size());
  Set::for_each_kind([&](auto k) {
    using Kind = typename Set::template Kind<k>;
    const auto& store = set.template store<k>();
    for (size_t i = 0; i < Kind::size(store); ++i) bounds.push_back(Kind::bounds(Kind::hot(store, i)));
  });
  return bounds;
}

template <class Set>
std::optional<PrimitiveHit> NaiveAggregate<Set>::closest_hit(const Ray& ray, Interval range) const {
  std::optional<PrimitiveHit> closest;
  const TriangleRay prepared(ray);
  for (size_t slot = 0; slot < flat_.size(); ++slot)
    if (const std::optional<PrimitiveHit> hit = flat_.intersect(slot, prepared, range)) {
      closest = hit;
      range.max = hit->t;
    }
  return closest;
}

template <class Set>
bool NaiveAggregate<Set>::occluded(const Ray& ray, Interval range) const {
  const TriangleRay prepared(ray);
  for (size_t slot = 0; slot < flat_.size(); ++slot)
    if (flat_.occludes(slot, prepared, range)) return true;
  return false;
}

template <class Set>
BvhAggregate<Set>::BvhAggregate(std::shared_ptr<const Set> primitives, const BvhBuildOptions& options)
    : primitives_(primitives->size()) {
  bvh_ = build_bvh(FlatPrimitives<Set>::bounds_in_set_order(*primitives), options);
  stats_ = bvh_.stats();
  if (!options.wide) {
    // The slots are copied out in leaf order straight away (slot = leaf slot), not copied and then
    // reordered: on a 10^6-triangle mesh that saves 40 MB of writing.
    flat_ = FlatPrimitives<Set>(std::move(primitives), bvh_.order);
    return;
  }
  wide_ = collapse_to_wide(bvh_);
  store_wide_leaves(std::move(primitives), options);
  // The wide tree holds its own boxes and leaves: the binary nodes (a third of the memory on the
  // bunny) and the leaf order are not read again.
  bvh_ = Bvh{};
}

template <class Set>
void BvhAggregate<Set>::store_wide_leaves(std::shared_ptr<const Set> primitives, const BvhBuildOptions& options) {
  // A leaf becomes a pack when it holds one to four triangles (for a compact pack, of one mesh and
  // within kCompactSpread vertex numbers) and the scene's triangle test is the watertight one,
  // whose answers the pack's test gives bit for bit; any other leaf keeps its primitives in slots,
  // copied out in leaf order.
  const std::array<std::uint32_t, Set::kKinds + 1> first = first_of_each_kind(*primitives);
  bool may_pack = false;
  if constexpr (kTriangles < Set::kKinds) {
    may_pack = options.triangle_packs &&
               primitives->template store<kTriangles>().method != TriangleMethod::moller_trumbore;
    compact_ = may_pack && options.compact_packs;
    triangles_ = &primitives->template store<kTriangles>();
  }
  std::vector<std::uint32_t> loose;  // the set numbers of the slots' primitives, in leaf order
  // First, in node order, which leaves become packs (numbered in that order): each pack's leaf, as
  // its first entry in the leaf order and its count.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> packed_leaves;
  if (may_pack) packed_leaves.reserve(stats_.leaves);
  for (WideBvhNode& node : wide_->nodes)
    for (int i = 0; i < WideBvhNode::kWidth; ++i) {
      if (node.count[i] == 0) continue;
      const std::span<const std::uint32_t> leaf(bvh_.order.data() + node.child[i], node.count[i]);
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
          triangle[lane] = bvh_.order[at + (lane < count ? lane : 0)] - first[kTriangles];
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
        for (size_t lane = 0; lane < TrianglePack::kLanes; ++lane) corners[lane] = TriangleKind::hot(store, triangle[lane]);
        pack_triangles_[k] = triangle;
        packs_[k] = TrianglePack(std::span<const TriangleCorners>(corners.data(), count));
      }
    });
  }
  flat_ = FlatPrimitives<Set>(std::move(primitives), loose);
}

template <class Set>
std::optional<PrimitiveHit> BvhAggregate<Set>::closest_hit(const Ray& ray, Interval range) const {
  // The traversal reports hits nearer and nearer, so the last one reported is the nearest. Only
  // its surface parameters are kept, field by field, and which primitive it is comes from the
  // slot at the end: copying the whole optional hit at every hit stalls on a failed
  // store-to-load forward (it is written in pieces and read back at once; docs/stage5.md).
  float b1 = 0.0f, b2 = 0.0f;
  const TriangleRay prepared(ray);
  auto hit_primitive = [&](std::uint32_t slot, Interval r) -> std::optional<float> {
    const std::optional<PrimitiveHit> hit = flat_.test(slot, prepared, r);
    if (!hit) return std::nullopt;
    b1 = hit->b1;
    b2 = hit->b2;
    return hit->t;
  };
  if (!wide_) {
    const auto found = bvh_closest_hit(bvh_, ray, range, hit_primitive);
    if (!found) return std::nullopt;
    PrimitiveHit nearest{found->first, b1, b2};
    flat_.name(nearest, found->second);
    return nearest;
  }
  // In the 4-wide tree: the nearest hit's slot, or its pack and lane (4 pack + lane) when packed.
  std::uint32_t where = 0;
  bool in_pack = false;
  auto hit_slots = slot_by_slot(hit_primitive, where);
  auto search = [&](auto compact) __attribute__((always_inline)) {
    auto hit_leaf = [&](std::uint32_t child, std::uint32_t count, Interval r)
                        __attribute__((always_inline)) -> std::optional<float> {
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
    return wide_bvh_closest_hit(*wide_, ray, range, hit_leaf);
  };
  // The default layout's code laid out as the straight path: on the Cornell box 0.25 % fewer
  // instructions per path than without the hint (callgrind).
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
    flat_.name(nearest, where);
  }
  return nearest;
}

template <class Set>
bool BvhAggregate<Set>::occluded(const Ray& ray, Interval range) const {
  const TriangleRay prepared(ray);
  auto hits_primitive = [&](std::uint32_t slot, Interval r) { return flat_.occludes(slot, prepared, r); };
  if (!wide_) return bvh_any_hit(bvh_, ray, range, hits_primitive);
  auto search = [&](auto compact) {
    auto hits_leaf = [&](std::uint32_t child, std::uint32_t count, Interval r) __attribute__((always_inline)) {
      if (count & kPackedLeaf) return intersect_pack<decltype(compact)::value>(child, prepared, r).has_value();
      for (std::uint32_t slot = child; slot < child + count; ++slot)
        if (hits_primitive(slot, r)) return true;
      return false;
    };
    return wide_bvh_any_hit(*wide_, ray, range, hits_leaf);
  };
  return compact_ ? search(std::true_type{}) : search(std::false_type{});
}

}  // namespace rt
