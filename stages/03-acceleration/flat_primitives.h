// Stage 3: a set's primitives of every kind as one array of slots in a chosen order, which is what
// an aggregate's leaves point into.
#pragma once

#include "02-whitted/primitives.h"
#include "common/aabb.h"
#include "common/cache_line_allocator.h"

#include <array>
#include <memory>
#include <numeric>
#include <optional>
#include <span>
#include <vector>

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

  // A traversal's test of a slot: t of its hit, with b1, b2 written out. A traversal keeps only
  // the nearest hit's parameters, field by field, and which primitive it is from the slot at the
  // end: copying the whole optional hit at every hit stalls on a failed store-to-load forward (it
  // is written in pieces and read back at once; docs/stage5.md).
  std::optional<float> hit_distance(size_t slot, const TriangleRay& ray, Interval range, float& b1, float& b2) const {
    const std::optional<PrimitiveHit> hit = test(slot, ray, range);
    if (!hit) return std::nullopt;
    b1 = hit->b1;
    b2 = hit->b2;
    return hit->t;
  }
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

// first[k]: the number of kind k's first primitive in the set's numbering; first[kKinds] is the
// number of primitives.
template <class Set>
std::array<std::uint32_t, Set::kKinds + 1> first_of_each_kind(const Set& set) {
  std::array<std::uint32_t, Set::kKinds + 1> first{};
  Set::for_each_kind(
      [&](auto k) { first[k + 1] = first[k] + std::uint32_t(Set::template Kind<k>::size(set.template store<k>())); });
  return first;
}

inline std::vector<std::uint32_t> numbers_up_to(size_t count) {
  std::vector<std::uint32_t> numbers(count);
  std::iota(numbers.begin(), numbers.end(), 0u);
  return numbers;
}

template <class Set>
FlatPrimitives<Set>::FlatPrimitives(std::shared_ptr<const Set> set) : FlatPrimitives(set, numbers_up_to(set->size())) {}

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

}  // namespace rt
