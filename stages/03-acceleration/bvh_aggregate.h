// Stage 3: the two aggregates stage 3 compares, behind stage 2's Aggregate interface: the naive one
// (every primitive against every ray: the correctness oracle and the baseline) and the BVH, over
// spheres and triangles together.
#pragma once

#include "02-whitted/aggregate.h"
#include "03-acceleration/bvh.h"
#include "03-acceleration/wide_bvh.h"

#include <array>

namespace rt {

// The primitives as one list: spheres first, then every mesh's triangles, each triangle's three
// corners copied out. `reorder` puts the list in a BVH's leaf order, so that the triangles of a
// leaf sit next to each other in memory.
struct FlatPrimitives {
  std::shared_ptr<const PrimitiveSet> set;
  std::vector<std::uint32_t> primitive;      // per entry: spheres 0..S-1, then triangles S, S+1, ...
  std::vector<std::array<Vec3, 3>> corners;  // per entry (unused for spheres)
  std::vector<std::uint32_t> triangle_mesh;  // per triangle (index primitive - S): its mesh ...
  std::vector<std::uint32_t> triangle_index; // ... and its index there

  explicit FlatPrimitives(std::shared_ptr<const PrimitiveSet> primitives);
  size_t size() const { return primitive.size(); }
  Aabb bounds(size_t entry) const;
  void reorder(const std::vector<std::uint32_t>& order);
  // The hit distance of entry `i` within `range`; `triangle_hit` receives the barycentrics.
  std::optional<float> hit(size_t i, const TriangleRay& ray, Interval range, TriangleHit* triangle_hit = nullptr) const;
  PrimitiveHit record(size_t i, float t, const TriangleHit& triangle_hit) const;
};

class NaiveAggregate : public Aggregate {
 public:
  explicit NaiveAggregate(std::shared_ptr<const PrimitiveSet> primitives) : flat_(std::move(primitives)) {}
  std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const override;
  bool occluded(const Ray& ray, Interval range) const override;

 private:
  FlatPrimitives flat_;
};

class BvhAggregate : public Aggregate {
 public:
  BvhAggregate(std::shared_ptr<const PrimitiveSet> primitives, const BvhBuildOptions& options);
  std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const override;
  bool occluded(const Ray& ray, Interval range) const override;

  const Bvh& bvh() const { return bvh_; }
  const std::optional<WideBvh>& wide_bvh() const { return wide_; }
  // Memory of the acceleration structure: nodes, leaf order and the copied corners.
  size_t bytes() const;

 private:
  FlatPrimitives flat_;
  Bvh bvh_;
  std::optional<WideBvh> wide_;  // when built with BvhBuildOptions::wide
};

// For WhittedScene: `--accel naive|median|middle|sah`.
AggregateFactory naive_aggregate_factory();
AggregateFactory bvh_aggregate_factory(const BvhBuildOptions& options);

}  // namespace rt
