#include "03-acceleration/wide_bvh.h"


namespace rt {
namespace {

class Collapser {
 public:
  explicit Collapser(const Bvh& bvh) : bvh_(bvh) {}

  WideBvh collapse() && {
    const bool empty = bvh_.nodes.empty() || (bvh_.nodes[0].is_leaf && bvh_.nodes[0].count == 0);
    if (!empty) {
      wide_.bounds = bvh_.nodes[0].bounds;
      // A root that is itself a leaf becomes the only child of a wide root.
      if (bvh_.nodes[0].is_leaf) make_node({0});
      else make_node({bvh_.nodes[0].offset, bvh_.nodes[0].offset + 1});
    }
    return std::move(wide_);
  }

 private:
  // Makes a wide node over the given binary nodes, opening interior ones (largest box first)
  // until there are four; returns its index.
  std::uint32_t make_node(std::vector<std::uint32_t> children) {
    while (children.size() < size_t(WideBvhNode::kWidth)) {
      auto largest = children.end();
      for (auto c = children.begin(); c != children.end(); ++c)
        if (!bvh_.nodes[*c].is_leaf &&
            (largest == children.end() || bvh_.nodes[*c].bounds.half_area() > bvh_.nodes[*largest].bounds.half_area()))
          largest = c;
      if (largest == children.end()) break;
      const std::uint32_t first = bvh_.nodes[*largest].offset;
      *largest = first;
      children.push_back(first + 1);
    }
    const auto index = std::uint32_t(wide_.nodes.size());
    wide_.nodes.emplace_back();
    WideBvhNode node{};
    for (int i = 0; i < WideBvhNode::kWidth; ++i) {
      Aabb box;  // empty unless the child exists
      if (size_t(i) < children.size()) {
        const BvhNode& child = bvh_.nodes[children[size_t(i)]];
        box = child.bounds;
        node.child[i] = child.is_leaf ? child.offset : make_node({child.offset, child.offset + 1});
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
