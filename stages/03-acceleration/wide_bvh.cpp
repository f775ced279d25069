#include "03-acceleration/wide_bvh.h"

#include <array>

namespace rt {
namespace {

class Collapser {
 public:
  explicit Collapser(const Bvh& bvh) : bvh_(bvh) {}

  WideBvh collapse() && {
    const bool empty = bvh_.nodes.empty() || (bvh_.nodes[0].is_leaf && bvh_.nodes[0].count == 0);
    if (!empty) {
      wide_.bounds = bvh_.nodes[0].bounds;
      // Each wide node opens at least one interior binary node, and a binary tree has fewer
      // interior nodes than half its nodes: room for all of them, so no node is copied twice.
      wide_.nodes.reserve(bvh_.nodes.size() / 2 + 1);
      // A root that is itself a leaf becomes the only child of a wide root.
      if (bvh_.nodes[0].is_leaf) make_node(Children{{0}, 1});
      else make_node(pair_of(bvh_.nodes[0]));
    }
    return std::move(wide_);
  }

 private:
  // Up to four binary nodes (a fixed array: a wide node per call, no allocation for each).
  struct Children {
    std::array<std::uint32_t, WideBvhNode::kWidth> node;
    int size;
  };
  static Children pair_of(const BvhNode& interior) { return Children{{interior.offset, interior.offset + 1}, 2}; }

  // Makes a wide node over the given binary nodes, opening interior ones (largest box first)
  // until there are four; returns its index.
  std::uint32_t make_node(Children children) {
    while (children.size < WideBvhNode::kWidth) {
      int largest = -1;
      for (int c = 0; c < children.size; ++c) {
        const BvhNode& node = bvh_.nodes[children.node[size_t(c)]];
        if (!node.is_leaf &&
            (largest < 0 || node.bounds.half_area() > bvh_.nodes[children.node[size_t(largest)]].bounds.half_area()))
          largest = c;
      }
      if (largest < 0) break;
      const std::uint32_t first = bvh_.nodes[children.node[size_t(largest)]].offset;
      children.node[size_t(largest)] = first;
      children.node[size_t(children.size++)] = first + 1;
    }
    const auto index = std::uint32_t(wide_.nodes.size());
    wide_.nodes.emplace_back();
    WideBvhNode node{};
    for (int i = 0; i < WideBvhNode::kWidth; ++i) {
      Aabb box;  // empty unless the child exists
      if (i < children.size) {
        const BvhNode& child = bvh_.nodes[children.node[size_t(i)]];
        box = child.bounds;
        node.child[i] = child.is_leaf ? child.offset : make_node(pair_of(child));
        node.count[i] = child.is_leaf ? child.count : 0u;
      }
      for (int axis = 0; axis < 3; ++axis) {
        node.bounds[0][axis][i] = box.lo[axis];
        node.bounds[1][axis][i] = box.hi[axis];
      }
    }
    wide_.nodes[index] = node;
    return index;
  }

  const Bvh& bvh_;
  WideBvh wide_;
};

}  // namespace

WideBvh collapse_to_wide(const Bvh& bvh) { return Collapser(bvh).collapse(); }

}  // namespace rt
