#pragma once
// Visibility between two points by casting a ray against every patch of the
// scene, brute force (lesson 09, the V(x, y) of the radiosity equation).
// Lesson 08's structures make this fast (patch_occluders.hpp); here clarity comes first.
#include <optional>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// The parameter t of the point a + t(b − a) where the segment crosses the
// convex patch, if it does so with t strictly inside (t_min, t_max). The
// plane hit is t = −(D + N·a)/(N·(b − a)) with D = −N·v₀ (erratum 2 of docs/errata.md: the
// notes drop the minus sign); a segment parallel to the plane never hits.
// Containment: the hit is on the inner side of every edge of the
// counter-clockwise polygon (edges and vertices count as inside).
std::optional<double> segment_patch_hit(const Point3& a, const Point3& b, const Patch& patch, double t_min,
                                        double t_max);

// True when no patch of `occluders` crosses the open segment from a to b.
// The ends are excluded by a relative margin of 1e-9 so that the patches
// the segment starts and ends on never block it (they may be in the list).
bool mutually_visible(const Point3& a, const Point3& b, const std::vector<Patch>& occluders);

}  // namespace illum
