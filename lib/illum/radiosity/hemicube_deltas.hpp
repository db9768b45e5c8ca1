#pragma once
// Exercise unit of lesson 10: students write hemicube_deltas.cpp.
// Delta form factors of the hemicube, lesson 10 ("Método del Hemicubo").
//
// The hemicube is a unit half-cube placed on a patch: the top face is the
// square z = 1, |x|, |y| ≤ 1; the four side faces are the half squares
// x = ±1 and y = ±1 with 0 ≤ z ≤ 1. Each face is divided into pixels of side
// 2/resolution. A pixel of area ΔA at position p on a face sees a solid
// angle whose form factor from the hemicube's centre is
//   ΔF = cos φ_i cos φ_p / (π r²) ΔA                    (lesson 10, eq. 10.1)
// where φ_i is the angle between p and the patch's normal and φ_p the angle
// between p and the face's normal.
// * Top face (z = 1): r² = x² + y² + 1, cos φ_i = cos φ_p = 1/r, so
//     ΔF = ΔA / (π (x² + y² + 1)²)                      (eq. 10.2)
// * Side face x = 1 with face coordinates (y, z): r² = y² + z² + 1,
//   cos φ_i = z/r, cos φ_p = 1/r, so
//     ΔF = z ΔA / (π (y² + z² + 1)²)                    (eq. 10.3, erratum 6 of docs/errata.md:
//   the notes write r = √(x² + y² + 1), the top face's r, before using the
//   right one.)
//
// Evaluating these at the pixel's centre (the notes' "midpoint" rule) makes
// the deltas sum to 1 only up to O(1/resolution²). Integrating the same
// functions exactly over each pixel makes them sum to 1 to round-off: the
// integrals have closed forms (the form factor from a differential area to
// a rectangle, eq. 10.4 and 10.5), evaluated at the pixel's four corners.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace illum {

// ΔF of a top-face pixel of area `pixel_area` centred at (x, y), eq. 10.2.
double top_face_delta(double x, double y, double pixel_area);

// ΔF of a side-face pixel of area `pixel_area` centred at face coordinates
// (y, z), z the height above the patch, eq. 10.3 (erratum 6 of docs/errata.md).
double side_face_delta(double y, double z, double pixel_area);

// ∫₀ˣ∫₀ʸ 1/(π (s² + t² + 1)²) dt ds: the form factor from the hemicube's
// centre to the top-face rectangle [0, x] × [0, y] (signed: odd in x and y),
//   G(x, y) = 1/(2π) [ x/√(1+x²) atan(y/√(1+x²)) + y/√(1+y²) atan(x/√(1+y²)) ]   (eq. 10.4)
double top_face_corner(double x, double y);

// ∫₀ʸ∫₀ᶻ t/(π (s² + t² + 1)²) dt ds: the form factor from the centre to the
// side-face rectangle [0, y] × [0, z] (odd in y, even in z),
//   H(y, z) = 1/(2π) [ atan y − atan(y/√(1+z²)) / √(1+z²) ]   (eq. 10.5)
double side_face_corner(double y, double z);

enum class DeltaRule {
  midpoint,  // the notes: ΔF evaluated at the pixel's centre times ΔA, in both tables
  exact,     // ΔF integrated exactly over the pixel (corner formulas)
};

// The delta form factors of every pixel, precomputed once per resolution.
// `top` has resolution × resolution entries, row-major: entry (row, col) is
// the pixel centred at x = −1 + (col + ½)·2/res, y = −1 + (row + ½)·2/res.
// `side` has (resolution/2) × resolution entries, row-major: entry
// (row, col) is centred at horizontal coordinate −1 + (col + ½)·2/res and
// height z = (row + ½)·2/res. The four side faces share this table (they are
// congruent and their deltas depend only on |horizontal| and z).
struct HemicubeDeltas {
  int resolution = 0;
  std::vector<double> top;
  std::vector<double> side;
};

// Throws std::invalid_argument unless resolution is even and ≥ 2.
HemicubeDeltas make_hemicube_deltas(int resolution, DeltaRule rule = DeltaRule::exact);

// The row accumulation ("sumar las contribuciones a cada trozo"): for
// every pixel p of a face, row[items[p]] += deltas[p] when items[p] ≥ 0
// (negative items are empty pixels or occluders that receive nothing).
// Throws std::invalid_argument when items and deltas differ in length, either
// way (one item and one delta per pixel; checked before anything is added),
// or when an item ≥ 0 is not an index of row.
void accumulate_face(std::span<const std::int32_t> items, std::span<const double> deltas,
                     std::span<double> row);

}  // namespace illum
