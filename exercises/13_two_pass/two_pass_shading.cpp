// Lesson 13 exercise: pass two at a hit.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/two_pass_shading.hpp.
#include "illum/radiosity/two_pass_shading.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"
#include "illum/geometry/polygon.hpp"  // drop_axis, largest_axis: lesson 02's projection

namespace illum {

// Task 2. (u, v) of a point of a meshed quad (inverse bilinear map) or triangle (barycentric).
Vec2 surface_coordinates(std::span<const Point3> polygon, const Point3& x) {
  throw NotImplemented(
      "surface_coordinates",
      "drop the normal's largest component (lesson 02, §3), solve cross(g, f) v² + (cross(e, f) + "
      "cross(h, g)) v + cross(h, e) = 0 with the stable roots (sign(0) = +1), then u = (h − f v)/(e + g v) "
      "(lesson 13, §3)");
}

// Task 3. The patch holding (u, v) and its corners' weights.
PatchCell locate_patch(const Vec2& uv, int n, int m, int vertex_count) {
  throw NotImplemented(
      "locate_patch",
      "quad: cell (⌊u n⌋, ⌊v m⌋) clamped to the last one, bilinear weights; triangle (m "
      "ignored): row j starts at j (2n − j), down when s + t > 1, past the hypotenuse (s, t)/(s "
      "+ t) (lesson 13, §3)");
}

// Task 4. I = D + k_r I_r + k_t I_t.
Color second_pass_radiance(const Color& diffuse, const Color& k_r, const Color& reflected, const Color& k_t,
                           const Color& transmitted) {
  throw NotImplemented(
      "second_pass_radiance",
      "add k_r I_r and k_t I_t channel by channel, only where the factor is not zero; refuse "
      "k_r + k_t > 1 (lesson 13, eq. 13.2)");
}

}  // namespace illum
