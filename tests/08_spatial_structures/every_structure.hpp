#pragma once
// Every spatial structure of lesson 08 over one set, by name, for the hard
// cases that must hold through all of them: brute force, the uniform grid (its
// default resolution and a fine one), the octree, the teaching BVH, and the
// production BVH with each of its kernels, SSE2, AVX and AVX2 with fused
// multiply-adds (CompactBvh::use_kernel; a kernel the processor lacks runs the
// best one it has, and its name says so), at the default leaf size and at 16,
// where the wide kernels filter two packs at once. And the comparison with
// brute force, the slow exact method they must agree with.
#include <doctest/doctest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "illum/accel/brute_force.hpp"
#include "illum/accel/bvh.hpp"
#include "illum/accel/octree.hpp"
#include "illum/accel/production/compact_bvh.hpp"
#include "illum/accel/triangle_accel.hpp"
#include "illum/accel/uniform_grid.hpp"

namespace illum::test08 {

struct Structure {
  std::string name;
  std::unique_ptr<TriangleAccel> accel;
};

inline std::vector<Structure> every_structure(const TriangleSet& set) {
  std::vector<Structure> all;
  all.push_back({"brute_force", std::make_unique<BruteForce>(set)});
  all.push_back({"grid (default resolution)", make_accel(set, {.kind = AccelKind::grid})});
  all.push_back({"grid (resolution 37)", std::make_unique<UniformGrid>(set, GridSettings{.resolution = 37})});
  all.push_back({"octree", make_accel(set, {.kind = AccelKind::octree})});
  all.push_back({"bvh", std::make_unique<Bvh>(set, BvhSettings{})});
  for (const int leaf : {4, 16})
    for (const CompactBvh::Kernel kernel : CompactBvh::all_kernels) {
      auto bvh = std::make_unique<CompactBvh>(set, BvhSettings{.leaf_size = leaf});
      const CompactBvh::Kernel used = bvh->use_kernel(kernel);
      all.push_back(
          {std::string("bvh, ") + to_string(kernel) + " kernel" +
               (used == kernel ? "" : std::string(" (not on this processor: ") + to_string(used) + ")") +
               ", leaf size " + std::to_string(leaf),
           std::move(bvh)});
    }
  return all;
}

// The structures whose walk the student writes (lesson 08's exercise): the uniform grid (the
// 3DDA, at its default resolution and a fine one) and the teaching BVH (bvh_traversal.cpp).
// The graded twins of the hard cases run these alone.
inline std::vector<Structure> student_structures(const TriangleSet& set) {
  std::vector<Structure> all;
  all.push_back({"grid (default resolution)", make_accel(set, {.kind = AccelKind::grid})});
  all.push_back({"grid (resolution 37)", std::make_unique<UniformGrid>(set, GridSettings{.resolution = 37})});
  all.push_back({"bvh", std::make_unique<Bvh>(set, BvhSettings{})});
  return all;
}

// Brute force's answers to a list of rays: the closest hit and whether anything is in range.
struct Reference {
  std::vector<std::optional<AccelHit>> closest;
  std::vector<bool> occluded;
};

inline Reference brute_force_answers(const TriangleSet& set, const std::vector<Ray>& rays) {
  const BruteForce brute(set);
  TraversalCounters counters;
  Reference r;
  for (const Ray& ray : rays) {
    r.closest.push_back(brute.intersect(ray, counters));
    r.occluded.push_back(brute.occluded(ray, counters));
  }
  return r;
}

// The same hit or miss as brute force, at the same s, by the same triangle unless another
// triangle is hit at exactly that s too (a tie), and the same any-hit answer. Returns the
// number of rays that disagree and reports the first three.
inline int disagreements(const TriangleAccel& accel, const TriangleSet& set, const std::vector<Ray>& rays,
                         const Reference& reference) {
  TraversalCounters counters;
  int wrong = 0;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const Ray& ray = rays[k];
    const std::optional<AccelHit>& expected = reference.closest[k];
    const std::optional<AccelHit> got = accel.intersect(ray, counters);
    bool same = expected.has_value() == got.has_value();
    if (same && expected) {
      const auto other = intersect(ray, set.triangles[got->triangle]);
      same = expected->hit.s == got->hit.s && other && other->s == expected->hit.s;
    }
    same = same && accel.occluded(ray, counters) == reference.occluded[k];
    if (!same && ++wrong <= 3) {
      INFO(accel.name() << ": ray (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z
                        << ") + s·(" << ray.direction.x << ", " << ray.direction.y << ", " << ray.direction.z
                        << "), s in [" << ray.range.lo << ", " << ray.range.hi << "]; brute force "
                        << (expected ? expected->hit.s : -1.0) << ", structure "
                        << (got ? got->hit.s : -1.0));
      CHECK_MESSAGE(false, "the structure must return brute force's closest hit and any-hit answer");
    }
  }
  return wrong;
}

}  // namespace illum::test08
