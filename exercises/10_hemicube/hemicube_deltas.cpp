// Lesson 10 exercise: the hemicube's delta form factors and the row accumulation.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/hemicube_deltas.hpp.
// The rasteriser (hemicube_raster.cpp) and the driver (hemicube.cpp) are provided.
#include "illum/radiosity/hemicube_deltas.hpp"

#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. ΔF of a top-face pixel: cos φ_i cos φ_p / (π r²) ΔA with r² = x² + y² + 1.
double top_face_delta(double x, double y, double pixel_area) {
  throw NotImplemented("top_face_delta", "both cosines are 1/r on the top face (lesson 10, §2, eq. 10.2)");
}

// Task 2. ΔF of a side-face pixel at face coordinates (y, z): mind erratum 6 of docs/errata.md.
double side_face_delta(double y, double z, double pixel_area) {
  throw NotImplemented("side_face_delta",
                       "on the face x = 1, r² = y² + z² + 1, cos φ_i = z/r, cos φ_p = 1/r (lesson 10, §2, "
                       "eq. 10.3, erratum 6)");
}

// Task 3. The closed-form integrals of the two delta functions over [0, x] × [0, y]
// (top) and [0, y] × [0, z] (side).
double top_face_corner(double x, double y) {
  throw NotImplemented(
      "top_face_corner",
      "the form factor to a parallel rectangle with a corner above (lesson 10, §3, eq. 10.4)");
}

double side_face_corner(double y, double z) {
  throw NotImplemented("side_face_corner", "integrate over z first, then over y (lesson 10, §3, eq. 10.5)");
}

// Task 4. The table of every pixel's delta, by the midpoint rule or exactly
// (corner formula at the pixel's four corners). Refuse odd or non-positive
// resolutions with std::invalid_argument.
HemicubeDeltas make_hemicube_deltas(int resolution, DeltaRule rule) {
  throw NotImplemented("make_hemicube_deltas",
                       "top: res × res pixels of side 2/res over [−1, 1]²; sides: res/2 rows over 0 ≤ z ≤ 1 "
                       "(lesson 10, §3)");
}

// Task 5. F_ij = Σ ΔF over the pixels whose item is j.
void accumulate_face(std::span<const std::int32_t> items, std::span<const double> deltas,
                     std::span<double> row) {
  throw NotImplemented("accumulate_face", "skip negative items; add, do not overwrite (lesson 10, §4)");
}

}  // namespace illum
