// Not course material: read bvh_traversal.cpp (the exercise) for the BVH traversal.
#pragma once
// Production code, apart from the course (lib/illum/accel/production/): the
// same tree as the teaching Bvh, laid out and traversed for speed. A student
// need not read it; lesson 08 (§5) says what it changes and measures what it
// buys (out/lesson08/bvh_layouts.md), and `--accel bvh` runs a
// lesson's program on the exercise's traversal instead.
//
// The production BVH, lesson 08 (§5): the same binned-SAH tree as Bvh, its
// nodes grouped into eight-child nodes (about three levels at a time; the
// grouping with the least total box area, see WidePlan) and laid out for speed.
// Bvh's traversal (bvh_traversal.cpp) is the teaching version, the
// exercise; this is the one the scene, the radiosity visibility and the
// Embree comparison use ("compact_bvh"; the teaching one is "bvh").
//
// What changes, and why each is safe:
//   * a node holds its (up to) eight children's boxes, in float, rounded
//     OUTWARD (lo down, hi up), so each float box contains the double one;
//     one node is four cache lines, and a third as many nodes lie on a path
//     (each node a dependent memory access: the cost a profile shows);
//   * the eight boxes are clipped four at a time (SSE2, four float lanes,
//     the x86-64 baseline) or, where the processor has AVX (checked once at
//     run time), all eight at once by the same operations lane by lane
//     (the whole traversal is then compiled for AVX). The ray
//     origin is moved by 2⁻²¹·|o| (more than its rounding to float) towards
//     each box's outside, and the exit widened by 2γ₃ (float): the float
//     test can only accept more than the exact one, never less;
//   * children are visited nearest entry first; the others are stacked with
//     their entry and skipped when popped if a hit closer than that entry
//     (plus 10⁻⁵ relative, the float test's slack) has been found;
//   * per ray, the inverse direction and its signs are computed once; the
//     near plane of each axis is chosen by sign, no swap. 0·∞ = NaN (a ray
//     lying in a face plane) is dropped by the order of the max/min operands:
//     inside, as in slab_test.hpp;
//   * a leaf's triangles are stored four at a time (TrianglePack: float
//     vertex and edges, one SSE lane per triangle) and tested at once by
//     Möller–Trumbore in float, as a filter: a lane is dropped only when its
//     barycentrics or its t miss by more than an a-priori bound on the float
//     rounding (K·(|o|+|v0|)·|ω|·|e|, K = 2⁻¹⁷, about twice the worst case of
//     the float operations, all norms ∞-norms), so a true hit is never
//     dropped; a grazing lane (|det| within its bound, sign unknown) passes.
//     Every surviving lane goes to lesson 03's watertight test in double,
//     which decides: hit/miss and t are the exact test's, edges and vertices
//     included. A lane hit for sure (every margin beyond the bound) has that
//     test deferred to the end of the ray, its double data loading meanwhile,
//     and culls at once by an upper bound on its t. The bound assumes no
//     float overflow or underflow (coordinates and edges within about 10^±15).
//   * subtrees of at most min(16, leaf_size) triangles are merged into one
//     leaf (at most four packs): a pack test is cheaper than a box test and
//     a miss in cache. leaf_size stays what it is in Bvh, the most triangles
//     in a leaf; the Embree comparison builds with leaf_size 16. The AVX
//     traversal filters a leaf's packs two at a time in eight lanes.
// Counters: one node visit per child box tested, one triangle test per (used) lane filtered.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "illum/accel/bvh.hpp"
#include "illum/accel/triangle_accel.hpp"
#include "illum/system/huge_pages.hpp"

namespace illum {

// Eight children: for each a reference (a leaf's first TrianglePack and its count of triangles,
// or the index of an inner node: compact_bvh_ref) and its box planes [plane][child], planes 0–2 the
// lo of x, y, z and 3–5 the hi. An unused slot has an empty box (lo = +∞, hi = −∞) that no ray
// enters. The references come first, in the line that also holds the lo of x: the box test loads
// all four lines at once, so the references are in cache when it picks a child.
constexpr int compact_bvh_width = 8;
struct alignas(64) CompactBvhNode {
  std::uint32_t child[compact_bvh_width];
  float planes[6][compact_bvh_width];
  std::uint32_t unused[compact_bvh_width];  // 0 (the build keeps a leaf's first triangle here)
};
static_assert(sizeof(CompactBvhNode) == 256);

// A child reference: the low 24 bits an index (of a node, or of a leaf's first pack), the high 8
// the leaf's count of triangles (0: an inner node). Each leaf holds at most 255 triangles (as
// BvhSettings allows) and the build refuses a tree of 2^24 nodes or packs (64 million triangles).
constexpr int compact_bvh_index_bits = 24;
constexpr std::uint32_t compact_bvh_ref(std::uint32_t index, std::uint32_t count) {
  return index | count << compact_bvh_index_bits;
}

// The filter's view of four triangles, [axis][lane]: a vertex, the two edges
// from it, their ∞-norms for the rounding bound, and the triangles' ids. A leaf of n triangles
// owns ⌈n/4⌉ consecutive packs; its last pack's unused lanes are masked out.
struct alignas(16) TrianglePack {
  float v0[3][4];
  float e1[3][4];
  float e2[3][4];
  float v0_size[4];     // ‖v0‖∞ (of the double vertex), rounded up
  float edge_size[4];   // max(‖e1‖∞, ‖e2‖∞) (of the double edges), rounded up
  std::uint32_t id[4];  // the set's index of each lane's triangle: in the lines the filter reads
};
static_assert(sizeof(TrianglePack) == 192);

class CompactBvh final : public TriangleAccel {
 public:
  // Builds a Bvh with `settings` and lays it out; throws as Bvh does.
  CompactBvh(const TriangleSet& set, const BvhSettings& settings);

  std::optional<AccelHit> intersect(const Ray& ray, TraversalCounters& counters) const override;
  bool occluded(const Ray& ray, TraversalCounters& counters) const override;
  std::size_t memory_bytes() const override;
  std::string_view name() const override { return "compact_bvh"; }

  std::size_t node_count() const { return nodes_.size(); }

  // The traversal's kernels: the x86-64 baseline (SSE2, four lanes), AVX (eight lanes) and AVX2 with
  // fused multiply-adds. Each gives the same hits (the exact test decides every one). The default is
  // the best the processor has (asked once, at run time); use_kernel picks a lower one, so that tests
  // check every kernel on one machine, and returns the kernel now used: the best the processor has
  // at or below `wanted`.
  enum class Kernel { sse2, avx, avx2_fma };
  static constexpr Kernel all_kernels[] = {Kernel::sse2, Kernel::avx, Kernel::avx2_fma};
  Kernel use_kernel(Kernel wanted);
  Kernel kernel() const { return kernel_; }

 private:
  // intersect's traversal for one kernel; each is compiled for its instruction set, and called only
  // where the processor has it.
  template <Kernel k>
  std::optional<AccelHit> closest(const Ray& ray, TraversalCounters& counters) const;
  std::optional<AccelHit> intersect_avx2_fma(const Ray& ray, TraversalCounters& counters) const;
  std::optional<AccelHit> intersect_avx(const Ray& ray, TraversalCounters& counters) const;
  std::optional<AccelHit> intersect_sse2(const Ray& ray, TraversalCounters& counters) const;

  Kernel kernel_ = Kernel::sse2;

  HugePageVector<CompactBvhNode> nodes_;
  HugePageVector<TrianglePack> packs_;  // in leaf order, and one for padding
  HugePageVector<Triangle>
      triangles_;  // triangles_[4·pack + lane], for the exact test (unused lanes: copies)
};

// "sse2", "avx", "avx2_fma".
const char* to_string(CompactBvh::Kernel kernel);

// The inner nodes of a Bvh's tree (Bvh::nodes(): children follow their parent, the second at `first`)
// that CompactBvh makes its eight-child nodes: of the choices that leave every eight-child node at most
// eight slots (the leaves and eight-child nodes met first below it), the one with the least total
// surface area of eight-child nodes, found by dynamic programming. wide[n] for each node; the root is
// one unless it is a leaf.
std::vector<bool> eight_child_nodes(const std::vector<BvhNode>& tree);

}  // namespace illum
