#pragma once
// Lesson 04's solids and their shading: the classic CSG models the
// demonstration draws (a die, a lens, a drilled cube) and those the
// coincident-face study needs (a blind hole and a square pocket whose
// openings lie in a face of the box, a thin coin). Built from the library's
// primitives and tree (geometry/csg_tree.hpp).
#include "illum/core/ray.hpp"
#include "illum/geometry/csg_tree.hpp"

namespace illum::lesson04 {

// Surface tags: which colour a surface gets in the shaded images.
enum Tag { body = 0, pip = 1, second = 1, drill_x = 1, drill_y = 2, drill_z = 3 };

// A die: the rounded cube [−1,1]³ ∩ ball(1.38), minus 21 small balls for the
// pips (opposite faces add up to seven).
CsgNodePtr make_die();

// A lens: the common part of two unit balls whose centres are 1.2 apart.
CsgNodePtr make_lens();

// A drilled cube: [−1,1]³ minus three cylinders along x, y and z that
// overshoot the faces (the modeller's habit that avoids coincident faces).
CsgNodePtr make_drilled_cube();

// A blind hole whose opening lies exactly in the box's top face z = 1: the
// cylinder's top cap and the box face are the same plane, computed two ways.
CsgNodePtr make_blind_hole();

// A square pocket sharing the top face: both faces from the same slab arithmetic.
CsgNodePtr make_pocket();

// A coin of thickness coin_thickness: a slab ∩ a ball, a genuinely thin solid.
constexpr double coin_thickness = 1e-4;
CsgNodePtr make_coin();

// The colour of a ray that hits nothing.
Color background(const Ray& ray);

// Lambert shading under one directional light plus a little ambient light,
// coloured by the tag of the surface that made the hit.
Color shade(const Ray& ray, const CsgHit& hit);

// The outward normal as a colour, (n + 1)/2.
Color normal_colour(const Ray& ray, const CsgHit& hit);

}  // namespace illum::lesson04
