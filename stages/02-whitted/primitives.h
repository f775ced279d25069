// Stage 2: the bounded primitives of a scene, open to new kinds. A kind (SphereKind and
// TriangleKind here, DiskKind in stage 4) is intersected by the stage that teaches it; a
// PrimitiveSet holds one store per kind, and every aggregate (stage 2's linear one, stage 3's BVHs)
// is a template over the set, so each kind's test is called directly: no virtual call per
// primitive, only a switch on its kind (visit_kind). Adding a kind is one kind class in the stage that teaches it plus
// its name in that stage's kind list (docs/design.md, "Registration points").
//
// The contract of a kind: a class of static functions, written out here once.
//   using Store       everything of this kind in one scene
//   using Hot         what the intersection test reads of one primitive; a BVH copies it per leaf
//                     slot, so that a leaf's primitives lie next to each other in memory
//   add(Store&, const Shape&, int shape) -> bool
//                     takes the scene file's shape number `shape` when it is of this kind
//   size(const Store&) -> size_t
//   hot(const Store&, size_t i) -> Hot (or a reference to one)
//   bounds(const Hot&) -> Aabb
//   intersect(const Store&, const Hot&, const TriangleRay&, Interval) -> std::optional<PrimitiveHit>
//                     the hit with t strictly inside the interval; fills t, b1, b2 (not kind, index).
//                     TriangleRay is the ray with what the triangle tests prepare once per ray;
//                     other kinds read its .ray
//   hit_record(const Store&, const PrimitiveHit&, const Ray&) -> Hit
//                     the full record of a hit this kind reported, through make_hit (common/hit.h)
//   runs(const Store&) -> std::vector<PrimitiveRun>
//                     consecutive primitives that stage 2's linear aggregate tests behind one
//                     bounding sphere (a mesh); together they cover [0, size)
#pragma once

#include "02-whitted/triangle_ray.h"
#include "common/aabb.h"
#include "common/hit.h"
#include "common/interval.h"
#include "common/scene.h"

#include <cstdint>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace rt {

// Which primitive a ray hit, as an aggregate reports it: 20 bytes, so a traversal carries no more
// than it needs. The full Hit is made once, for the nearest hit only (PrimitiveSet::hit_record).
struct PrimitiveHit {
  float t;
  float b1 = 0.0f, b2 = 0.0f;  // the kind's own surface parameters: a triangle's barycentrics
  std::uint32_t index = 0;     // the primitive within its kind's store
  std::uint8_t kind = 0;       // the kind's place in its PrimitiveSet's list
};

// Primitives [first, last) of one kind.
struct PrimitiveRun {
  std::uint32_t first, last;
};

// Calls f(std::integral_constant<size_t, K>{}) for the K < N that equals `kind`. A chain of
// compares of constants, which the compiler turns into a switch: each kind's function is then a
// direct (usually inlined) call.
template <size_t N, size_t K = 0, class F>
[[gnu::always_inline]] inline decltype(auto) visit_kind(size_t kind, F&& f) {
  if constexpr (K + 1 == N) {
    return f(std::integral_constant<size_t, K>{});
  } else {
    if (kind == K) return f(std::integral_constant<size_t, K>{});
    return visit_kind<N, K + 1>(kind, std::forward<F>(f));
  }
}

template <class... Kinds>
class PrimitiveSet {
 public:
  static constexpr size_t kKinds = sizeof...(Kinds);
  static_assert(kKinds >= 1 && kKinds <= 255, "a PrimitiveHit names its kind in one byte");
  template <size_t K>
  using Kind = std::tuple_element_t<K, std::tuple<Kinds...>>;
  // The hot data of a primitive of any kind (what a BVH keeps per leaf slot); index() is its kind.
  using AnyHot = std::variant<typename Kinds::Hot...>;

  template <size_t K>
  auto& store() { return std::get<K>(stores_); }
  template <size_t K>
  const auto& store() const { return std::get<K>(stores_); }
  // A kind's place in the list: what PrimitiveHit::kind says for it.
  template <class Wanted, size_t K = 0>
  static constexpr size_t index_of() {
    static_assert(K < kKinds, "this kind is not in the set");
    if constexpr (std::is_same_v<Kind<K>, Wanted>) return K;
    else return index_of<Wanted, K + 1>();
  }
  template <class Wanted>
  static constexpr bool contains() {
    return (std::is_same_v<Kinds, Wanted> || ...);
  }
  // The store of a kind named by type, for the code that knows which kind it wants.
  template <class Wanted>
  auto& store_of() { return store<index_of<Wanted>()>(); }
  template <class Wanted>
  const auto& store_of() const { return store<index_of<Wanted>()>(); }

  // Offers the scene file's shape `shape` to each kind in the list's order: the first that takes it
  // keeps it (so a kind listed before TriangleKind may claim some quads). False when none does.
  bool add(const Shape& description, int shape) {
    bool taken = false;
    for_each_kind([&](auto k) { taken = taken || Kind<k>::add(store<k>(), description, shape); });
    return taken;
  }

  // Calls f(std::integral_constant<size_t, K>{}) for every kind, in the list's order.
  template <class F>
  static void for_each_kind(F&& f) {
    [&]<size_t... K>(std::index_sequence<K...>) { (f(std::integral_constant<size_t, K>{}), ...); }
    (std::index_sequence_for<Kinds...>{});
  }

  size_t size() const {
    size_t total = 0;
    for_each_kind([&](auto k) { total += Kind<k>::size(store<k>()); });
    return total;
  }

  Hit hit_record(const PrimitiveHit& hit, const Ray& ray) const {
    return visit_kind<kKinds>(hit.kind, [&](auto k) { return Kind<k>::hit_record(store<k>(), hit, ray); });
  }

 private:
  std::tuple<typename Kinds::Store...> stores_;
};

// What kinds whose primitives are single placed shapes (a sphere, a disk) share: a list of
// Placed<G>, the geometry itself as the hot data, and no runs worth a bounding sphere. Such a kind
// adds bounds, intersect and hit_record.
template <class G>
struct PlacedGeometryKind {
  using Store = std::vector<Placed<G>>;
  using Hot = G;

  static bool add(Store& store, const Shape& shape, int index) {
    const G* geometry = std::get_if<G>(&shape.geometry);
    if (geometry) store.push_back({*geometry, shape.material, index});
    return geometry != nullptr;
  }
  static size_t size(const Store& store) { return store.size(); }
  static const G& hot(const Store& store, size_t i) { return store[i].geometry; }
  // Each primitive a run of its own: a sphere around one sphere or disk saves nothing.
  static std::vector<PrimitiveRun> runs(const Store& store) {
    std::vector<PrimitiveRun> runs;
    for (std::uint32_t i = 0; i < std::uint32_t(store.size()); ++i) runs.push_back({i, i + 1});
    return runs;
  }
};

}  // namespace rt
