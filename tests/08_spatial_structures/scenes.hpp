#pragma once
// Seeded test scenes and rays shared by lesson 08's test files.
#include <vector>

#include "illum/accel/triangle_set.hpp"
#include "illum/core/random.hpp"
#include "illum/core/ray.hpp"

namespace illum::test08 {

// A soup of `count` triangles of mixed sizes (edges 0.02 … 0.8) in a box
// whose corners are not exact in binary, some long and thin.
inline TriangleSet triangle_soup(int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Triangle> tris;
  while (static_cast<int>(tris.size()) < count) {
    const Point3 c(rng.uniform(-2.3, 3.1), rng.uniform(-1.7, 2.9), rng.uniform(-0.9, 4.3));
    const double size = 0.02 + 0.78 * rng.uniform() * rng.uniform();
    const Vec3 e1(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Vec3 e2(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (length(cross(e1, e2)) < 1e-3) continue;
    tris.emplace_back(c, c + size * e1, c + size * e2);
  }
  return TriangleSet::from_triangles(std::move(tris));
}

inline Vec3 random_direction(Rng& rng) {
  for (;;) {
    const Vec3 v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double l2 = dot(v, v);
    if (l2 > 1e-4 && l2 <= 1.0) return v / std::sqrt(l2);
  }
}

// Rays of every kind: origins outside and inside the scene's box, random
// directions, and one in three axis-parallel with an origin that shares two
// coordinates with a vertex (so the ray lies in a plane of some box's face:
// the slab test's 0·∞ case).
inline std::vector<Ray> mixed_rays(const TriangleSet& set, int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Ray> rays;
  for (int k = 0; k < count; ++k) {
    if (k % 3 == 2) {
      const Triangle& t = set.triangles[rng.below(static_cast<std::uint32_t>(set.size()))];
      const Point3 v = (k % 2 == 0) ? t.a : t.c;
      const int axis = static_cast<int>(rng.below(3));
      Vec3 d(0.0);
      d[axis] = rng.uniform() < 0.5 ? 1.0 : -1.0;
      Point3 o = v;
      o[axis] = rng.uniform(-4.0, 6.0);
      rays.emplace_back(o, d);
    } else {
      const Point3 o(rng.uniform(-4.0, 5.0), rng.uniform(-3.5, 4.5), rng.uniform(-2.5, 6.0));
      rays.emplace_back(o, random_direction(rng));
    }
  }
  return rays;
}

}  // namespace illum::test08
