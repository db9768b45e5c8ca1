#pragma once
// Exercise unit of lesson 13: students write two_pass_shading.cpp.
// Pass two at a hit (lesson 13, §3): reading the radiosity solution where an
// eye ray meets a meshed surface, and adding the specular rays.
//
// A surface is meshed the way mesh_quad / mesh_triangle mesh it (patch.hpp):
//   quad p0 p1 p2 p3:  P(u, v) = (1−u)(1−v) p0 + u(1−v) p1 + uv p2 + (1−u)v p3,
//                      n × m cells, cell (i, j) is patch j·n + i with corners
//                      P(i/n, j/m), P((i+1)/n, j/m), P((i+1)/n, (j+1)/m), P(i/n, (j+1)/m);
//   triangle a b c:    P(u, v) = a + u (b − a) + v (c − a),  u, v ≥ 0, u + v ≤ 1,
//                      n² triangles; row j (0 … n−1) holds, for i = 0 … n−j−1, the
//                      "up" triangle (i, j), (i+1, j), (i, j+1) and, while
//                      i + j + 1 < n, the "down" triangle (i+1, j), (i+1, j+1), (i, j+1),
//                      in that order (row j starts at patch j (2n − j)).
// Grid point (i, j) is P(i/n, j/m) (m = n for a triangle).
#include <array>
#include <cstddef>
#include <span>

#include "illum/core/vec.hpp"

namespace illum {

// Task 2. (u, v) of the point x of a planar convex quad (4 vertices) or triangle (3) in the
// parametrisation above. For a quad this inverts the bilinear map: with
// e = p1 − p0, f = p3 − p0, g = p0 − p1 + p2 − p3, h = x − p0, all four made
// 2-D by dropping the largest component of the quad's normal, as lesson 02,
// §3 projects a polygon (drop_axis(v, largest_axis(n)), geometry/polygon.hpp;
// n from the quad's edge vectors, e.g. (p1 − p0) × (p3 − p0)), and
// cross(a, b) = a.x b.y − a.y b.x, v solves
//   k2 v² + k1 v + k0 = 0,  k2 = cross(g, f), k1 = cross(e, f) + cross(h, g), k0 = cross(h, e),
// a linear equation when g = 0 (a parallelogram: |k2| ≤ 1e-12·|k1|), and then
// u = (h − f v) / (e + g v) (the component with the larger |denominator|).
// The two roots by the stable pair q = −(k1 + sign(k1)·√Δ)/2, q/k2 and k0/q,
// with sign(0) = +1 (k1 is exactly 0 on a line across some quads, and a
// sign of 0 makes q = 0 and loses both roots); of the two, the one in
// [0, 1] (with a tolerance of 1e-9); when both or neither are, the one nearer
// ½ (the point may lie a rounding outside). The result is clamped to [0, 1]², and never
// NaN: the discriminant Δ = k1² − 4 k2 k0, ≥ 0 for a point of the quad, can
// round a hair below 0 where the two roots nearly meet (at the short side of a
// nearly triangular quad), and is then taken as 0.
// For a triangle, (u, v) are the barycentric weights of b and c, in double. Throws
// std::invalid_argument unless the polygon has 3 or 4 vertices.
Vec2 surface_coordinates(std::span<const Point3> polygon, const Point3& x);

// The patch of a meshed surface that holds the point of coordinates (u, v),
// and the weight of each of its corners (in the patch's vertex order) in
// the point: bilinear in the cell for a quad, barycentric for a triangle
// (unused corners 0). Weights are ≥ 0 and add up to 1.
struct PatchCell {
  std::size_t patch = 0;           // index among the surface's patches
  std::array<double, 4> weight{};  // corner weights
  int corners = 4;                 // 4 for a quad's cell, 3 for a triangle
};

// Task 3. `vertex_count` is 4 (a quad meshed n × m) or 3 (a triangle meshed n²:
// m is ignored, any value, 0 included). With i, j the cell's column and row
// and s = u·n − i, t = v·m − j (v·n − j on a triangle) the point's place in it:
// * quad: i = ⌊u·n⌋, j = ⌊v·m⌋, each clamped to the last cell (a point on the
//   far edge u = 1 belongs to the last cell, not to one past the end); weights
//   (1−s)(1−t), s(1−t), st, (1−s)t of the cell's corners in mesh order;
// * triangle: j = ⌊v·n⌋ clamped to n − 1, i = ⌊u·n⌋ clamped to the row's last
//   column n − 1 − j; the "down" triangle (i, j) when s + t > 1 (no
//   tolerance), with weights (1 − t, s + t − 1, 1 − s); else the "up" triangle,
//   weights (1 − s − t, s, t). A point on the diagonal s + t = 1 an up and a
//   down triangle share may go to either (both give the same weights to the
//   two corners of that side, and 0 to the third). In the row's last cell there
//   is no down triangle: a point on or a rounding error past the hypotenuse
//   u + v = 1 (s + t ≥ 1) belongs to the up triangle, pulled back onto the
//   hypotenuse along the line from the cell's corner (i, j): s and t each
//   capped at 1, then both divided by s + t (weights (0, s, t)/(s + t)), not
//   moved to the nearest point of the hypotenuse.
// The patch index is always below the surface's patch count (n·m, or n²). A
// (u, v) a rounding error outside [0, 1]² is taken at the nearest point of the
// square: s and t kept in [0, 1] (weights stay ≥ 0 and add up to 1). Throws
// std::invalid_argument when n < 1, when vertex_count is 4 and m < 1, or when
// vertex_count is not 3 or 4.
PatchCell locate_patch(const Vec2& uv, int n, int m, int vertex_count);

// Task 4. What the eye sees at a hit of pass two (lesson 13, eq. 13.2):
//   I = D + k_r·I_r + k_t·I_t
// where D is the diffuse part (B(x) read from pass one on a meshed surface,
// the local model's own intensity elsewhere). A factor that is zero in a
// channel adds nothing there, even when its ray was not cast and the value
// passed is not a number. Throws std::invalid_argument when a factor is
// negative, or when k_r + k_t > 1 in a channel (its message contains
// "k_r + k_t"); the bound has no tolerance: a sum of exactly 1 is allowed, the
// scene loader refuses the same sums.
Color second_pass_radiance(const Color& diffuse, const Color& k_r, const Color& reflected, const Color& k_t,
                           const Color& transmitted);

}  // namespace illum
