#include "illum/geometry/csg_tree.hpp"

#include <cmath>

#include "illum/core/error.hpp"

namespace illum {

namespace {

CsgNodePtr inner(CsgOperation op, const CsgNodePtr& a, const CsgNodePtr& b, const char* message) {
  require(a != nullptr && b != nullptr, message);
  auto node = std::make_shared<CsgNode>();
  node->is_leaf = false;
  node->op = op;
  node->left = a;
  node->right = b;
  return node;
}

CsgNodePtr balanced_union(const std::vector<CsgNodePtr>& solids, std::size_t first, std::size_t last) {
  if (last - first == 1) return solids[first];
  const std::size_t middle = first + (last - first) / 2;
  return csg_union(balanced_union(solids, first, middle), balanced_union(solids, middle, last));
}

// Roundoff in the box test must never prune a primitive that its exact test
// would hit, so boxes are padded by a few parts in 10⁹.
SolidBounds padded(const SolidBounds& b) {
  if (b.empty()) return b;
  const Vec3 pad = 1e-9 * (Vec3(1.0) + glm::abs(b.lo) + glm::abs(b.hi));
  SolidBounds out = b;
  for (int k = 0; k < 3; ++k) {
    if (std::isfinite(pad[k])) out.lo[k] -= pad[k], out.hi[k] += pad[k];
  }
  return out;
}

}  // namespace

CsgNodePtr csg_solid(const SolidPrimitive& primitive, int tag) {
  auto node = std::make_shared<CsgNode>();
  node->is_leaf = true;
  node->primitive = primitive;
  node->tag = tag;
  return node;
}

CsgNodePtr csg_union(const CsgNodePtr& a, const CsgNodePtr& b) {
  return inner(CsgOperation::unite, a, b, "csg_union: an operand is an empty (null) CSG node");
}

CsgNodePtr csg_intersection(const CsgNodePtr& a, const CsgNodePtr& b) {
  return inner(CsgOperation::intersect, a, b, "csg_intersection: an operand is an empty (null) CSG node");
}

CsgNodePtr csg_difference(const CsgNodePtr& a, const CsgNodePtr& b) {
  return inner(CsgOperation::subtract, a, b, "csg_difference: an operand is an empty (null) CSG node");
}

CsgNodePtr csg_union_all(const std::vector<CsgNodePtr>& solids) {
  require(!solids.empty(), "csg_union_all: the list of solids is empty");
  for (const CsgNodePtr& solid : solids) require(solid != nullptr, "csg_union_all: a solid is null");
  return balanced_union(solids, 0, solids.size());
}

CsgCounters& CsgCounters::operator+=(const CsgCounters& other) {
  work += other.work;
  box_tests += other.box_tests;
  skipped_tests += other.skipped_tests;
  return *this;
}

CsgTree::CsgTree(const CsgNodePtr& root) {
  require(root != nullptr, "CsgTree: the root is an empty (null) CSG node");
  flatten(*root, 1);
  require(primitive_count() <= SpanList::capacity,
          "CsgTree: more than SpanList::capacity (64) primitives; their spans could overflow a SpanList");
}

int CsgTree::flatten(const CsgNode& node, int level) {
  depth_ = std::max(depth_, level);
  const int index = static_cast<int>(nodes_.size());
  if (node.is_leaf) {
    nodes_.push_back({true, CsgOperation::unite, -1, -1, node.tag, node.primitive,
                      padded(primitive_bounds(node.primitive)), 1});
    return index;
  }
  require(node.left != nullptr && node.right != nullptr, "CsgTree: an inner node has an empty (null) child");
  nodes_.push_back({false, node.op, -1, -1, 0, node.primitive, SolidBounds{}, 0});  // primitive unused
  const int left = flatten(*node.left, level + 1);
  const int right = flatten(*node.right, level + 1);
  Node& n = nodes_[index];  // re-fetched: the vector may have grown
  n.left = left;
  n.right = right;
  n.leaves = nodes_[left].leaves + nodes_[right].leaves;
  const SolidBounds& a = nodes_[left].bounds;
  const SolidBounds& b = nodes_[right].bounds;
  switch (node.op) {
    case CsgOperation::unite:
      n.bounds = SolidBounds::hull(a, b);
      break;
    case CsgOperation::intersect:
      n.bounds = SolidBounds::overlap(a, b);
      break;
    case CsgOperation::subtract:
      n.bounds = a;
      break;  // A − B lies inside A
  }
  return index;
}

void CsgTree::spans(const Ray& ray, SpanList& out, const CsgOptions& options, CsgCounters& counters) const {
  evaluate(0, ray, out, options, counters);
}

void CsgTree::evaluate(int index, const Ray& ray, SpanList& out, const CsgOptions& options,
                       CsgCounters& counters) const {
  const Node& node = nodes_[index];
  out.clear();
  if (node.is_leaf) {
    ++counters.work.intersection_tests;
    Span span;
    if (primitive_span(ray, node.primitive, node.tag, span)) out.push_back(span);
    return;
  }
  // A leaf's own test is as cheap as a box test, so boxes are tried at inner nodes only.
  if (options.prune_with_bounds) {
    ++counters.box_tests;
    if (!node.bounds.crosses(ray)) {
      counters.skipped_tests += static_cast<std::uint64_t>(node.leaves);
      return;
    }
  }
  SpanList a, b;
  evaluate(node.left, ray, a, options, counters);
  if (a.empty() && node.op != CsgOperation::unite) {
    // ∅ ∩ B = ∅ − B = ∅: B need not be evaluated at all.
    counters.skipped_tests += static_cast<std::uint64_t>(nodes_[node.right].leaves);
    return;
  }
  evaluate(node.right, ray, b, options, counters);
  combine_spans(node.op, a, b, options.sliver_tolerance, out);
}

std::optional<CsgHit> intersect(const Ray& ray, const CsgTree& tree, const CsgOptions& options,
                                CsgCounters& counters) {
  ++counters.work.rays_cast;
  SpanList spans;
  tree.spans(ray, spans, options, counters);
  const std::optional<Crossing> nearest = nearest_crossing(spans, ray.range);
  if (!nearest) return std::nullopt;
  ++counters.work.hits;
  CsgHit hit;
  hit.s = nearest->boundary.s;
  hit.point = ray.at(hit.s);
  hit.normal = nearest->boundary.normal;
  hit.entering = nearest->entering;
  hit.surface = nearest->boundary.surface;
  return hit;
}

std::optional<CsgHit> intersect(const Ray& ray, const CsgTree& tree, const CsgOptions& options) {
  CsgCounters counters;
  return intersect(ray, tree, options, counters);
}

}  // namespace illum
