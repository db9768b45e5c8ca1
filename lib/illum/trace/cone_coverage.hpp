#pragma once
// Generalised rays, *rayos generalizados* (lesson 07, §6): a cone instead of a
// ray (Amanatides 1984). One cone per pixel, as wide as the pixel, carries the
// fraction of its cross-section each object covers, so a sphere's silhouette
// is antialiased without extra rays. For a sphere this fraction is the
// overlap of two discs on the view sphere: the cone's section (angular radius
// β) and the sphere's silhouette (angular radius α = asin(r/d)), their
// centres θ apart (small-angle approximation: discs in a plane).
#include "illum/core/vec.hpp"

namespace illum {

// The area common to two discs of radii r1, r2 ≥ 0 whose centres are d ≥ 0
// apart: 0 when d ≥ r1 + r2, π·min(r1, r2)² when d ≤ |r1 − r2|, otherwise
// the lens r1²·acos(c1) + r2²·acos(c2) − ½√((−d+r1+r2)(d+r1−r2)(d−r1+r2)(d+r1+r2))
// with c1 = (d² + r1² − r2²)/(2 d r1), c2 likewise, computed in a form that
// stays accurate when the discs nearly touch (see the source).
double disc_overlap_area(double r1, double r2, double d);

// The angle between two directions, by atan2(|a × b|, a·b): accurate for
// nearly parallel vectors, where acos(a·b) loses half the digits.
double angle_between(const Vec3& a, const Vec3& b);

struct Cone {
  Point3 apex{0.0};
  Vec3 axis{0.0, 0.0, -1.0};  // unit
  double half_angle = 0.0;    // β > 0
};

// The fraction in [0, 1] of the cone's section covered by the sphere
// (centre, radius): 1 when the apex is inside it, 0 when it lies behind the apex.
double cone_sphere_coverage(const Cone& cone, const Point3& center, double radius);

}  // namespace illum
