// Stage 2: the interface of whatever finds a ray's hits among a scene's bounded primitives, and
// stage 2's own: every primitive tested in turn (LinearAggregate). Stage 3 builds bounding volume
// hierarchies behind the same interface, and the scene and the integrators do not change.
#pragma once

#include "01-ray-casting/sphere_intersection.h"
#include "02-whitted/primitives.h"

#include <array>
#include <functional>
#include <memory>

namespace rt {

class Aggregate {
 public:
  virtual ~Aggregate() = default;
  // The nearest primitive hit with t strictly inside `range`.
  virtual std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const = 0;
  // Whether any primitive is hit with t strictly inside `range`; may stop at the first.
  virtual bool occluded(const Ray& ray, Interval range) const = 0;
};

// Builds an aggregate over a primitive set; the aggregate may keep the shared pointer.
template <class Set>
using AggregateFactory = std::function<std::unique_ptr<Aggregate>(std::shared_ptr<const Set>)>;

// Stage 2's aggregate: every primitive of every kind, in the set's order, except that a run of at
// least 8 (a mesh, TriangleKind::runs) is tested only when the ray meets a sphere around it: below
// that the sphere test costs as much as the triangles it saves.
template <class Set>
class LinearAggregate : public Aggregate {
 public:
  explicit LinearAggregate(std::shared_ptr<const Set> primitives);
  std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const override {
    return search(ray, range, false);
  }
  bool occluded(const Ray& ray, Interval range) const override { return search(ray, range, true).has_value(); }

 private:
  static constexpr std::uint32_t kBoundedRunMinPrimitives = 8;
  struct BoundedRun {
    PrimitiveRun run;
    std::optional<Sphere> bound;
  };

  // Both queries in one loop: the nearest hit, or with `any_hit` the first one found.
  std::optional<PrimitiveHit> search(const Ray& ray, Interval range, bool any_hit) const;

  std::shared_ptr<const Set> primitives_;
  std::array<std::vector<BoundedRun>, Set::kKinds> runs_;  // per kind
};

template <class Set>
std::unique_ptr<Aggregate> make_linear_aggregate(std::shared_ptr<const Set> primitives) {
  return std::make_unique<LinearAggregate<Set>>(std::move(primitives));
}

// A sphere around a run's boxes, padded by a relative 1e-4 so that rounding in the sphere test can
// never reject a ray that hits a primitive inside.
Sphere bounding_sphere(const std::vector<Aabb>& boxes);

template <class Set>
LinearAggregate<Set>::LinearAggregate(std::shared_ptr<const Set> primitives) : primitives_(std::move(primitives)) {
  Set::for_each_kind([&](auto k) {
    using Kind = typename Set::template Kind<k>;
    const auto& store = primitives_->template store<k>();
    for (const PrimitiveRun& run : Kind::runs(store)) {
      std::optional<Sphere> bound;
      if (run.last - run.first >= kBoundedRunMinPrimitives) {
        std::vector<Aabb> boxes;
        for (std::uint32_t i = run.first; i < run.last; ++i) boxes.push_back(Kind::bounds(Kind::hot(store, i)));
        bound = bounding_sphere(boxes);
      }
      runs_[k].push_back({run, bound});
    }
  });
}

template <class Set>
std::optional<PrimitiveHit> LinearAggregate<Set>::search(const Ray& ray, Interval range, bool any_hit) const {
  std::optional<PrimitiveHit> found;
  const TriangleRay prepared(ray);
  Set::for_each_kind([&](auto k) {
    using Kind = typename Set::template Kind<k>;
    const auto& store = primitives_->template store<k>();
    for (const BoundedRun& r : runs_[k]) {
      if (any_hit && found) return;
      if (r.bound) {
        const std::optional<Interval> span = sphere_span(ray, *r.bound);
        if (!span || span->max <= range.min || span->min >= range.max) continue;
      }
      for (std::uint32_t i = r.run.first; i < r.run.last; ++i)
        if (std::optional<PrimitiveHit> hit = Kind::intersect(store, Kind::hot(store, i), prepared, range)) {
          hit->kind = std::uint8_t(k);
          hit->index = i;
          found = hit;
          if (any_hit) return;
          range.max = hit->t;
        }
    }
  });
  return found;
}

}  // namespace rt
