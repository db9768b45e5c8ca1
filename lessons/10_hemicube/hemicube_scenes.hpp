#pragma once
// Lesson 10's configurations and their exact form factors: Howell's closed
// forms and the contour formula of lesson 09 from a receiver at the origin,
// and the rooms the hemicube is placed in. Shared by the demonstration and
// the studies; the references are the library's
// (radiosity/rectangle_form_factors.hpp, radiosity/form_factor_analytic.hpp),
// independent of the hemicube.
#include <vector>

#include "illum/radiosity/patch.hpp"

namespace illum::lesson10 {

// Howell B-3: differential area to a parallel rectangle a × b with a corner above it at height c
// (the hemicube's top-face corner formula, eq. 10.4, scaled to height c).
double parallel_corner(double a, double b, double c);

// Howell B-4: differential area to a perpendicular rectangle of height a, width b at distance c
// (the side-face corner formula, eq. 10.5, scaled to distance c).
double perpendicular_corner(double a, double b, double c);

// The exact factor from the receiver at the origin (normal +z) to the front of `target`:
// the contour formula of lesson 09.
double exact_from_origin(const Patch& target);

// `polygon` as a patch whose front faces the origin.
Patch facing_origin(const std::vector<Point3>& polygon);

// The six faces of the box [lo, hi], meshed m × m, normals inwards (a room) or outwards (a block),
// their surfaces numbered from first_surface.
void add_box(std::vector<Patch>& patches, const Point3& lo, const Point3& hi, int m, bool inward,
             int first_surface);

// A closed unit room meshed m × m per wall with a floating block meshed k × k per face:
// every direction from every patch hits a front face, so every row sums to one.
std::vector<Patch> room_with_block(int m, int k);

// A small square of side s centred at c facing the origin.
std::vector<Point3> facing_square(const Point3& c, double s);

// A square receiver of half side `half` at the origin, normal +z.
Patch receiver_at_origin(double half = 0.01);

}  // namespace illum::lesson10
