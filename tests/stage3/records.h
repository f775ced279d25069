// The plain-data forms (tests/support/record.h) of stage 3's results that its graded tests record.
#pragma once

#include "02-whitted/primitives.h"
#include "03-acceleration/bvh.h"
#include "support/record.h"

namespace rt {

inline auto record_fields(PrimitiveHit& h) { return std::tie(h.t, h.b1, h.b2, h.index, h.kind); }
inline auto record_fields(BvhNode& n) { return std::tie(n.bounds, n.offset, n.count, n.axis, n.is_leaf); }

}  // namespace rt

namespace rt::testing {

// A binary tree: its nodes and its primitives' order, which the judge checks only by bounds-checked
// reads (the indices in it are the submission's).
template <>
struct Record<Bvh> {
  static void write(RecordWriter& out, const Bvh& bvh) {
    write_record(out, std::vector<BvhNode>(bvh.nodes.begin(), bvh.nodes.end()));
    write_record(out, std::vector<std::uint32_t>(bvh.order.begin(), bvh.order.end()));
  }
  static void read(RecordReader& in, Bvh& bvh) {
    std::vector<BvhNode> nodes;
    std::vector<std::uint32_t> order;
    read_record(in, nodes);
    read_record(in, order);
    bvh.nodes.assign(nodes.begin(), nodes.end());
    bvh.order.assign(order.begin(), order.end());
  }
};

}  // namespace rt::testing
