// Stage 3: the two aggregates stage 3 compares, behind stage 2's Aggregate interface: the naive one
// (every primitive against every ray: the correctness oracle and the baseline) and the BVH, over
// every kind of primitive of a set together.
#pragma once

#include "02-whitted/aggregate.h"
#include "03-acceleration/bvh.h"
#include "03-acceleration/flat_primitives.h"
#include "03-acceleration/packed_wide_bvh.h"

#include <optional>

namespace rt {

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

  // The binary tree, or, built with BvhBuildOptions::wide, the 4-wide one it was collapsed into
  // (packed_wide_bvh.h), which is then all the traversal reads: the binary tree is released.
  const Bvh& bvh() const { return bvh_; }
  const WideBvh* wide_bvh() const { return wide_ ? &wide_->tree() : nullptr; }
  // The binary tree's figures, taken before a collapse released it.
  const BvhStats& stats() const { return stats_; }
  size_t size() const { return primitives_; }
  // The 4-wide tree's leaves stored as triangle packs.
  size_t packs() const { return wide_ ? wide_->packs() : 0; }
  // Memory of the acceleration structure: nodes, leaf order, packs and the slots' copied primitives.
  size_t bytes() const {
    return bvh_.nodes.size() * sizeof(BvhNode) + bvh_.order.size() * sizeof(std::uint32_t) + flat_.bytes() +
           (wide_ ? wide_->bytes() : 0);
  }
  static constexpr std::uint32_t kPackedLeaf = PackedWideBvh<Set>::kPackedLeaf;

 private:
  size_t primitives_ = 0;
  FlatPrimitives<Set> flat_;  // the binary tree's leaves, in leaf order
  Bvh bvh_;
  BvhStats stats_;
  std::optional<PackedWideBvh<Set>> wide_;
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
  if (options.wide) {
    wide_.emplace(std::move(primitives), bvh_, options);
    // The binary nodes (a third of the memory on the bunny) and the leaf order are not read again.
    bvh_ = Bvh{};
    return;
  }
  // The slots are copied out in leaf order straight away (slot = leaf slot), not copied and then
  // reordered: on a 10^6-triangle mesh that saves 40 MB of writing.
  flat_ = FlatPrimitives<Set>(std::move(primitives), bvh_.order);
}

template <class Set>
std::optional<PrimitiveHit> BvhAggregate<Set>::closest_hit(const Ray& ray, Interval range) const {
  const TriangleRay prepared(ray);
  if (wide_) return wide_->closest_hit(ray, prepared, range);
  // The nearest hit's t, b1, b2 field by field (FlatPrimitives::hit_distance); which primitive it
  // is comes from its slot at the end.
  float b1 = 0.0f, b2 = 0.0f;
  auto hit_primitive = [&](std::uint32_t slot, Interval r) { return flat_.hit_distance(slot, prepared, r, b1, b2); };
  const auto found = bvh_closest_hit(bvh_, ray, range, hit_primitive);
  if (!found) return std::nullopt;
  PrimitiveHit nearest{found->first, b1, b2};
  flat_.name(nearest, found->second);
  return nearest;
}

template <class Set>
bool BvhAggregate<Set>::occluded(const Ray& ray, Interval range) const {
  const TriangleRay prepared(ray);
  if (wide_) return wide_->occluded(ray, prepared, range);
  auto hits_primitive = [&](std::uint32_t slot, Interval r) { return flat_.occludes(slot, prepared, r); };
  return bvh_any_hit(bvh_, ray, range, hits_primitive);
}

}  // namespace rt
