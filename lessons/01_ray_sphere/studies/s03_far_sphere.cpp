// §3 Where the textbook formula loses its digits: one far sphere in float.
//
// A sphere of radius 1 at distance 3000, seen in single precision through a
// narrow pinhole and shaded by its normal. With the notes' formula the
// discriminant B² − 4C cancels catastrophically and the disc is drawn as a blob of false hits; the
// stable form (§4) draws it whole.
#include <algorithm>

#include "illum/core/image.hpp"
#include "illum/geometry/sphere.hpp"
#include "studies.hpp"

namespace illum::lesson01 {
namespace {

template <bool stable>
Image render_far_sphere_float(int size, float distance) {
  Image image(size, size);
  const glm::vec3 center(0.0f, 0.0f, distance);
  const glm::vec3 light = glm::normalize(glm::vec3(-1.0f, 1.0f, -1.0f));
  const double half = 1.25 / distance;  // the image plane at distance 1 spans ±1.25 radii
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const glm::vec3 dir =
          glm::normalize(glm::vec3(static_cast<float>(half * (2.0 * (i + 0.5) / size - 1.0)),
                                   static_cast<float>(half * (1.0 - 2.0 * (j + 0.5) / size)), 1.0f));
      const SphereRoots<float> roots = stable ? sphere_roots_stable(glm::vec3(0.0f), dir, center, 1.0f)
                                              : sphere_roots_notes(glm::vec3(0.0f), dir, center, 1.0f);
      if (roots.count == 0) {
        image.at(i, j) = Color(0.02, 0.02, 0.05);
        continue;
      }
      const glm::vec3 n = (roots.s_near * dir - center);  // |n| should be r = 1
      const double shade = std::clamp(static_cast<double>(glm::dot(n, light)), 0.0, 1.0);
      image.at(i, j) = Color(0.1) + 0.85 * shade * Color(1.0, 0.85, 0.6);
    }
  return image;
}

}  // namespace

void s03_far_sphere(OutputFolder& out, const Settings& settings) {
  const int size = settings.quick ? 64 : 256;
  out.image(render_far_sphere_float<false>(size, 3000.0f), "far_sphere_notes_float",
            "A sphere of radius 1 at distance 3000 in float, notes' formula: B² − 4C cancels");
  out.image(render_far_sphere_float<true>(size, 3000.0f), "far_sphere_stable_float",
            "The same sphere in float, stable form: r² − d² from the distance to the line");
}

}  // namespace illum::lesson01
