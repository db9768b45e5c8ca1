#pragma once
// Lesson 02's polygon outlines: stars, a notched comb and regular polygons in
// a plane, placed in 3D. The demonstration (main.cpp) draws them; the cost
// study (studies/s07_parity_cost.cpp) times stars of growing vertex count.
#include <numbers>
#include <vector>

#include "illum/core/vec.hpp"

namespace illum::lesson02 {

// Points of a planar outline, placed in 3D: (u, v) ↦ centre + u·right + v·up.
std::vector<Point3> place(const std::vector<Vec2>& outline, const Point3& centre, const Vec3& right,
                          const Vec3& up);

// A star with `points` tips: 2·points vertices alternating between two radii.
std::vector<Vec2> star(int points, double outer, double inner, double phase = std::numbers::pi / 2);

// A comb: a bar with `teeth` teeth separated by rectangular notches.
std::vector<Vec2> comb(int teeth, double width, double height);

// A regular n-gon of radius r about `centre`, wound either way.
std::vector<Vec2> regular(int n, double r, Vec2 centre, bool clockwise);

}  // namespace illum::lesson02
