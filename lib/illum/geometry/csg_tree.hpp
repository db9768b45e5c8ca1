#pragma once
// Constructive solid geometry trees, lesson 04: solids built from primitives
// by union, intersection and difference, and the nearest hit of a ray with
// the result.
//
// Evaluation is recursive (Roth 1982): a leaf reports its primitive's span,
// an inner node combines its children's span lists (combine_spans), and the
// nearest crossing of the root's list inside the ray's range is the hit
// (nearest_crossing). Bounding boxes prune subtrees the ray misses: a
// subtree whose box the ray's line does not cross inside the ray's range
// adds no span there, so its primitives need not be tested (the notes'
// "volúmenes envolventes", applied to the tree).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "illum/core/counters.hpp"
#include "illum/core/ray.hpp"
#include "illum/geometry/solid_bounds.hpp"
#include "illum/geometry/solid_primitives.hpp"
#include "illum/geometry/span_combine.hpp"

namespace illum {

// A node of a CSG tree as the user builds it; immutable, shared by pointer
// so a subtree can be reused (the die's six faces share one pip).
struct CsgNode {
  bool is_leaf = true;
  SolidPrimitive primitive = SolidSphere(Point3(0.0), 1.0);  // leaves only
  int tag = 0;                                               // leaves only: the surface tag of its crossings
  CsgOperation op = CsgOperation::unite;                     // inner nodes only
  std::shared_ptr<const CsgNode> left, right;                // inner nodes only: A and B of A op B
};
using CsgNodePtr = std::shared_ptr<const CsgNode>;

// Builders. A null operand is an empty CSG node: std::invalid_argument.
CsgNodePtr csg_solid(const SolidPrimitive& primitive, int tag = 0);
CsgNodePtr csg_union(const CsgNodePtr& a, const CsgNodePtr& b);
CsgNodePtr csg_intersection(const CsgNodePtr& a, const CsgNodePtr& b);
CsgNodePtr csg_difference(const CsgNodePtr& a, const CsgNodePtr& b);
// The union of all the given solids as a balanced tree (depth ⌈log2 n⌉ + leaf),
// in the order given, so nearby solids listed together share a bounding box.
CsgNodePtr csg_union_all(const std::vector<CsgNodePtr>& solids);

struct CsgOptions {
  // Result spans no longer than this (in units of s) are dropped at every
  // inner node: the knob of the coincident-face study. 0 keeps every span of
  // positive length.
  double sliver_tolerance = 1e-9;
  // Skip subtrees whose bounding box the ray misses.
  bool prune_with_bounds = true;
};

struct CsgCounters {
  WorkCounters work;                // intersection_tests: primitive spans computed; hits
  std::uint64_t box_tests = 0;      // bounding-box tests at inner nodes
  std::uint64_t skipped_tests = 0;  // primitive tests avoided (pruned subtrees, empty left operands)

  CsgCounters& operator+=(const CsgCounters& other);
};

struct CsgHit {
  double s = 0;  // ray parameter, inside ray.range
  Point3 point;  // P0 + sω
  // Outward unit normal of the composite solid there, never flipped towards
  // the ray (the side is read from it, as for every hit struct: see
  // geometry/surface_hit.hpp).
  Vec3 normal;
  // Lesson 04's span view of the same fact: false when the ray leaves the
  // solid here (it started inside); equals dot(ω, normal) < 0.
  bool entering = true;
  int surface = 0;  // tag of the primitive whose surface it is
};

// A CSG tree flattened for evaluation: nodes in an array, each inner node
// with its children's indices and bounding box.
class CsgTree {
 public:
  // Throws std::invalid_argument when root is null or the tree has more
  // primitives than a SpanList can hold (SpanList::capacity).
  explicit CsgTree(const CsgNodePtr& root);

  int primitive_count() const { return nodes_.front().leaves; }
  int depth() const { return depth_; }
  const SolidBounds& bounds() const { return nodes_.front().bounds; }

  // The spans of the ray's line inside the solid (within the ray's range
  // where pruning skipped subtrees; exact everywhere else).
  void spans(const Ray& ray, SpanList& out, const CsgOptions& options, CsgCounters& counters) const;

 private:
  struct Node {
    bool is_leaf;
    CsgOperation op;
    int left = -1, right = -1;  // indices into nodes_
    int tag = 0;
    SolidPrimitive primitive;
    SolidBounds bounds;
    int leaves = 1;  // primitives in this subtree
  };
  int flatten(const CsgNode& node, int level);
  void evaluate(int index, const Ray& ray, SpanList& out, const CsgOptions& options,
                CsgCounters& counters) const;

  std::vector<Node> nodes_;
  int depth_ = 0;
};

// The nearest crossing of the ray with the solid inside ray.range.
std::optional<CsgHit> intersect(const Ray& ray, const CsgTree& tree, const CsgOptions& options,
                                CsgCounters& counters);
std::optional<CsgHit> intersect(const Ray& ray, const CsgTree& tree, const CsgOptions& options = {});

}  // namespace illum
