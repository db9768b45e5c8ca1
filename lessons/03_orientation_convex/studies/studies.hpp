#pragma once
// Lesson 03's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration) calls them in the
// text's order.
#include <cstdint>
#include <vector>

#include "illum/core/random.hpp"
#include "illum/geometry/polygon.hpp"
#include "illum/io/output_folder.hpp"

namespace illum::lesson03 {

// What the command line sets.
struct Settings {
  bool quick = false;      // --quick: small sizes
  std::uint64_t seed = 1;  // --seed
};

// A polygon in the plane z = 0 from its 2D outline.
inline Polygon flat(const std::vector<Vec2>& points) {
  std::vector<Point3> p;
  for (const Vec2& q : points) p.push_back({q.x, q.y, 0.0});
  return Polygon(p);
}

// §2: the sign of orient2d on Kettner's grid, naive and robust, and the rate
// of wrong signs against how nearly collinear three points are
// (studies/s02_orientation_signs.cpp). Draws from `rng` (§5 draws next).
void s02_orientation_signs(OutputFolder& out, const Settings& settings, Rng& rng);

// §4: nanoseconds per query of parity, winding and the convex test on
// regular n-gons (studies/s04_containment_cost.cpp).
void s04_containment_cost(OutputFolder& out, const Settings& settings);

// §5: cracks and double hits of Möller–Trumbore and the watertight test on
// rays aimed at a mesh's edges and vertices (studies/s05_watertight.cpp).
void s05_watertight(OutputFolder& out, const Settings& settings, Rng& rng);

}  // namespace illum::lesson03
