// Lesson 10 grading tests: the hemicube's delta form factors, the row
// accumulation, and whole rows checked against closed forms written here,
// independently of the implementation:
// * Howell's catalogue B-3: differential area to a parallel rectangle with a
//   corner above it, at height c, sides a and b (A = a/c, B = b/c):
//     F = 1/(2π) [ A/√(1+A²) atan(B/√(1+A²)) + B/√(1+B²) atan(A/√(1+B²)) ]
// * Howell B-4: differential area to a perpendicular rectangle of width b
//   and height a whose base edge lies in the element's plane, with one base
//   corner at the foot of the perpendicular from the element, at distance c
//   (X = a/b, Y = c/b):
//     F = 1/(2π) [ atan(1/Y) − Y/√(X²+Y²) atan(1/√(X²+Y²)) ]
// * Lambert's contour formula for a polygon above the element's tangent plane:
//     F = 1/(2π) Σ_k γ_k n·(R_k × R_{k+1})/|R_k × R_{k+1}|
// Each closed form is itself checked against Gauss–Legendre quadrature of
// cos θ_i cos θ_j / (π r²). The corner integrals G and H are signed (odd in
// x and y; odd in y and even in z), as their header states.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>
#include <vector>

#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/hemicube_deltas.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

constexpr double kPi = std::numbers::pi;

// Howell B-3, corner above, unit height after scaling.
double howell_b3(double a, double b, double c) {
  const double A = a / c, B = b / c;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * kPi);
}

// Howell B-4: height a (along the element's normal), width b, distance c.
double howell_b4(double a, double b, double c) {
  const double X = a / b, Y = c / b, s = std::sqrt(X * X + Y * Y);
  return (std::atan(1 / Y) - Y / s * std::atan(1 / s)) / (2 * kPi);
}

// Lambert's formula for a convex polygon wholly above the plane of the
// element at `p` with unit normal `n`.
double lambert_contour(const Point3& p, const Vec3& n, const std::vector<Point3>& polygon) {
  double sum = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec3 r0 = normalize(polygon[k] - p), r1 = normalize(polygon[(k + 1) % polygon.size()] - p);
    const Vec3 c = cross(r0, r1);
    const double gamma = std::atan2(length(c), dot(r0, r1));
    sum += gamma * dot(n, c) / length(c);
  }
  return std::abs(sum) / (2 * kPi);
}

// 2-D Gauss–Legendre quadrature with `panels` × `panels` panels of 8 points.
template <class F>
double integrate_2d(F&& f, double x0, double x1, double y0, double y1, int panels = 16) {
  static const std::array<double, 4> node{0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                          0.9602898564975363};
  static const std::array<double, 4> weight{0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                            0.1012285362903763};
  double total = 0;
  const double hx = (x1 - x0) / panels, hy = (y1 - y0) / panels;
  for (int px = 0; px < panels; ++px)
    for (int py = 0; py < panels; ++py) {
      const double cx = x0 + (px + 0.5) * hx, cy = y0 + (py + 0.5) * hy;
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
          const double u = (a < 4 ? -node[a] : node[a - 4]), wu = weight[a % 4];
          const double v = (b < 4 ? -node[b] : node[b - 4]), wv = weight[b % 4];
          total += wu * wv * f(cx + 0.5 * hx * u, cy + 0.5 * hy * v);
        }
    }
  return total * 0.25 * hx * hy;
}

// A small square receiver at the origin facing +z (the hemicube's centre is its centroid).
Patch receiver_at_origin(double half = 0.01) {
  return make_patch({{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}});
}

// A rectangle in the plane z = h, [x0, x1] × [y0, y1], facing down (−z).
Patch ceiling_rect(double x0, double x1, double y0, double y1, double h) {
  return make_patch({{x0, y0, h}, {x0, y1, h}, {x1, y1, h}, {x1, y0, h}});
}

// A rectangle in the plane x = c, [y0, y1] × [z0, z1], facing −x (towards the origin).
Patch wall_rect(double c, double y0, double y1, double z0, double z1) {
  return make_patch({{c, y0, z0}, {c, y0, z1}, {c, y1, z1}, {c, y1, z0}});
}

std::vector<double> row_of(const std::vector<Patch>& patches, int resolution, std::size_t i = 0,
                           double angle = 0.0) {
  const Hemicube hemicube(resolution);
  HemicubeBuffers buffers;
  std::vector<double> row(patches.size(), -1.0);
  hemicube.form_factor_row(patches, i, row, buffers, angle);
  return row;
}

// The unit cube meshed m × m per face, every normal pointing inwards.
std::vector<Patch> closed_cube(int m) {
  std::vector<Patch> box;
  auto add = [&](std::vector<Patch> v) { box.insert(box.end(), v.begin(), v.end()); };
  const Color rho(0.5);
  add(mesh_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, m, m, rho));
  add(mesh_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, m, m, rho));
  add(mesh_quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, m, m, rho));
  add(mesh_quad({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, m, m, rho));
  add(mesh_quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, m, m, rho));
  add(mesh_quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, m, m, rho));
  return box;
}

// The exact share of the unit hemicube's top face: four B-3 corners of 1 × 1 at height 1.
double top_share() { return 4 * howell_b3(1, 1, 1); }
// The exact share of one side face: two B-4 rectangles of height 1, width 1, distance 1.
double side_share() { return 2 * howell_b4(1, 1, 1); }

}  // namespace

TEST_SUITE("lesson10") {
  TEST_CASE("top_face_corner and side_face_corner are the integrals G and H (eq. 10.4–10.5), by quadrature" *
            doctest::description("task=3")) {
    // First the references the other tests use, checked against quadrature and each other.
    const double b3 = integrate_2d(
        [](double x, double y) { return 1 / (kPi * std::pow(x * x + y * y + 1, 2)); }, 0, 0.7, 0, 1.3);
    CHECK(howell_b3(0.7, 1.3, 1) == doctest::Approx(b3).epsilon(1e-12));
    const double b4 = integrate_2d(
        [](double y, double z) { return 2 * z / (kPi * std::pow(4 + y * y + z * z, 2)); }, 0, 0.9, 0, 1.7);
    INFO("B-4 at distance 2: F = ∫∫ (z/r)(2/r)/(π r²) dy dz");
    CHECK(howell_b4(1.7, 0.9, 2) == doctest::Approx(b4).epsilon(1e-12));
    CHECK(top_share() + 4 * side_share() == doctest::Approx(1.0).epsilon(1e-14));
    // The grading part: the student's corner functions must agree with the same integrals.
    CHECK(top_face_corner(0.7, 1.3) == doctest::Approx(b3).epsilon(1e-12));
    CHECK(side_face_corner(0.9 / 2, 1.7 / 2) == doctest::Approx(b4).epsilon(1e-12));
    // Signed integrals from 0, as make_hemicube_deltas needs them for the pixels left of and below the
    // centre: the integrand of G is even in s and t, so G is odd in x and in y; H's is even in s and odd
    // in t, so H is odd in y and even in z (a mirrored quadrant, G(|x|, |y|), fails here).
    CHECK(top_face_corner(-0.7, 1.3) == doctest::Approx(-b3).epsilon(1e-12));
    CHECK(top_face_corner(0.7, -1.3) == doctest::Approx(-b3).epsilon(1e-12));
    CHECK(top_face_corner(-0.7, -1.3) == doctest::Approx(b3).epsilon(1e-12));
    CHECK(side_face_corner(-0.9 / 2, 1.7 / 2) == doctest::Approx(-b4).epsilon(1e-12));
    CHECK(side_face_corner(0.9 / 2, -1.7 / 2) == doctest::Approx(b4).epsilon(1e-12));
  }

  TEST_CASE("top-face delta is cos φ_i cos φ_p / (π r²) ΔA (eq. 10.2)" * doctest::description("task=1")) {
    for (const auto& xy : std::vector<std::array<double, 2>>{{0, 0}, {0.3, -0.7}, {-0.95, 0.95}, {1, 0}}) {
      const double x = xy[0], y = xy[1];  // not a binding: INFO captures them (Clang < 16 cannot)
      const Vec3 p(x, y, 1);  // pixel centre on the top face; patch normal and face normal are both +z
      const double r = length(p), cos_i = p.z / r, cos_p = p.z / r;
      const double expected = cos_i * cos_p / (kPi * r * r) * 0.01;
      INFO("pixel at (" << x << ", " << y << ", 1): both cosines are 1/r, so ΔF = ΔA/(π r⁴)");
      CHECK(top_face_delta(x, y, 0.01) == doctest::Approx(expected).epsilon(1e-14));
    }
  }

  TEST_CASE("side-face delta uses r² = y² + z² + 1 (eq. 10.3, erratum 6)" * doctest::description("task=2")) {
    for (const auto& yz : std::vector<std::array<double, 2>>{{0, 0.5}, {0.4, 0.1}, {-0.9, 0.99}, {0.2, 0}}) {
      const double y = yz[0], z = yz[1];  // not a binding: INFO captures them (Clang < 16 cannot)
      const Vec3 p(1, y, z);              // pixel centre on the face x = 1
      const double r = length(p);
      const double cos_i = dot(p, Vec3(0, 0, 1)) / r;  // angle to the patch's normal: z/r
      const double cos_p = dot(p, Vec3(1, 0, 0)) / r;  // angle to the face's normal: 1/r
      const double expected = cos_i * cos_p / (kPi * r * r) * 0.02;
      INFO("pixel at (1, " << y << ", " << z << "): the notes' r = √(x² + y² + 1) is the top face's, "
                           << "on the side face r = √(y² + z² + 1)");
      CHECK(side_face_delta(y, z, 0.02) == doctest::Approx(expected).epsilon(1e-14));
    }
  }

  TEST_CASE("exact deltas sum to each face's share and to one, to round-off" *
            doctest::description("task=3,4")) {
    for (int res : {2, 10, 64, 200}) {
      const HemicubeDeltas d = make_hemicube_deltas(res, DeltaRule::exact);
      REQUIRE(d.top.size() == static_cast<std::size_t>(res * res));
      REQUIRE(d.side.size() == static_cast<std::size_t>(res * res / 2));
      double top = 0, side = 0;
      for (double v : d.top) top += v;
      for (double v : d.side) side += v;
      INFO("resolution " << res << ": the top face sees 4·B3(1,1,1) = " << top_share()
                         << ", each side 2·B4(1,1,1) = " << side_share());
      CHECK(top == doctest::Approx(top_share()).epsilon(1e-13));
      CHECK(side == doctest::Approx(side_share()).epsilon(1e-13));
      CHECK(top + 4 * side == doctest::Approx(1.0).epsilon(1e-13));
    }
  }

  TEST_CASE("midpoint deltas (the notes) converge to the face shares at second order" *
            doctest::description("task=1,2,4")) {
    double previous = 0;
    for (int res : {8, 16, 32, 64}) {
      const HemicubeDeltas d = make_hemicube_deltas(res, DeltaRule::midpoint);
      const double h = 2.0 / res;
      // The centre pixel is evaluated at its centre (−1 + h/2 + k h, …).
      CHECK(d.top[static_cast<std::size_t>(res / 2) * res + res / 2] ==
            doctest::Approx(h * h / (kPi * std::pow(2 * (h / 2) * (h / 2) + 1, 2))).epsilon(1e-14));
      double sum = 0;
      for (double v : d.top) sum += v;
      for (double v : d.side) sum += 4 * v;
      const double error = std::abs(sum - 1);
      INFO("resolution " << res << ": Σ ΔF − 1 = " << sum - 1 << "; the midpoint rule's error is O(h²)");
      CHECK(error > 1e-8);  // not exact: the pixel's delta varies across it
      if (previous > 0) {
        CHECK(error / previous > 0.2);
        CHECK(error / previous < 0.3);
      }
      previous = error;
    }
  }

  TEST_CASE("midpoint deltas: every pixel of the top and side tables at its own centre (eq. 10.2–10.3)" *
            doctest::description("task=1,2,4")) {
    // hemicube_deltas.hpp: with DeltaRule::midpoint, top entry (row, col) is ΔF at x = −1 + (col + ½)h,
    // y = −1 + (row + ½)h, and side entry (row, col) at horizontal −1 + (col + ½)h, height
    // z = (row + ½)h, each times ΔA = h², h = 2/res. Resolution 2 by hand: the side table has one row of
    // two pixels, at (∓½, z = ½) with ΔA = 1: ΔF = z/(π (y² + z² + 1)²) = 0.5/(π·1.5²) = 0.0707…;
    // evaluated at the pixel's edge (y = −1) it would be 0.5/(π·2.25²) = 0.0314…
    for (int res : {2, 4, 6}) {
      const HemicubeDeltas d = make_hemicube_deltas(res, DeltaRule::midpoint);
      const double h = 2.0 / res;
      REQUIRE(d.top.size() == static_cast<std::size_t>(res * res));
      REQUIRE(d.side.size() == static_cast<std::size_t>(res * res / 2));
      for (int row = 0; row < res; ++row)
        for (int col = 0; col < res; ++col) {
          const double x = -1 + (col + 0.5) * h, y = -1 + (row + 0.5) * h, r2 = x * x + y * y + 1;
          INFO("resolution " << res << ", top pixel (row " << row << ", column " << col << ") centred at ("
                             << x << ", " << y << ", 1)");
          CHECK(d.top[static_cast<std::size_t>(row * res + col)] ==
                doctest::Approx(h * h / (kPi * r2 * r2)).epsilon(1e-13));
        }
      for (int row = 0; row < res / 2; ++row)
        for (int col = 0; col < res; ++col) {
          const double y = -1 + (col + 0.5) * h, z = (row + 0.5) * h, r2 = y * y + z * z + 1;
          INFO("resolution " << res << ", side pixel (row " << row << ", column " << col
                             << ") centred at (1, " << y << ", " << z << ")");
          CHECK(d.side[static_cast<std::size_t>(row * res + col)] ==
                doctest::Approx(z * h * h / (kPi * r2 * r2)).epsilon(1e-13));
        }
    }
  }

  TEST_CASE("an open scene: a placement keeps nothing of the one before (the item buffers are cleared)" *
            doctest::description("task=3,4,5")) {
    // The receiver at the origin (facing up) sees the ceiling square ±0.6 at height 1 (facing down): four
    // B-3 corners, exact at resolution 10. A third patch at height 2 facing up sees nothing at all (nothing
    // lies above it, the scene is open): its row is exactly 0. Drawn with the same buffers right after the
    // receiver's row, a pixel the second placement does not draw must not keep the first one's item
    // (Hemicube::form_factor_row clears the five faces before drawing). Every graded scene above is
    // closed, where each pixel is drawn again.
    const std::vector<Patch> patches{
        receiver_at_origin(), ceiling_rect(-0.6, 0.6, -0.6, 0.6, 1),
        make_patch({{-0.5, -0.5, 2}, {0.5, -0.5, 2}, {0.5, 0.5, 2}, {-0.5, 0.5, 2}})};
    const Hemicube hemicube(10);
    HemicubeBuffers buffers;
    std::vector<double> first(3), second(3);
    hemicube.form_factor_row(patches, 0, first, buffers);
    hemicube.form_factor_row(patches, 2, second, buffers);
    CHECK(first[1] == doctest::Approx(4 * howell_b3(0.6, 0.6, 1)).epsilon(1e-12));
    CHECK_MESSAGE(second[0] == 0, "above everything, facing up: nothing is seen, F = 0");
    CHECK_MESSAGE(second[1] == 0, "the ceiling square is below the third patch: F = 0");
    // The parallel matrix reuses each thread's buffers row after row too.
    const FormFactorMatrix f = hemicube_form_factors(patches, 10);
    CHECK(f(2, 0) == 0);
    CHECK(f(2, 1) == 0);
    CHECK(f(0, 1) == doctest::Approx(4 * howell_b3(0.6, 0.6, 1)).epsilon(1e-12));
  }

  TEST_CASE("the row accumulation adds each pixel's delta to the patch it shows" *
            doctest::description("task=5")) {
    const std::vector<std::int32_t> items{0, -1, 2, 0, -2, 2, 2};
    const std::vector<double> deltas{0.1, 0.2, 0.3, 0.4, 0.5, 0.01, 0.001};
    std::vector<double> row{10, 20, 30};
    accumulate_face(items, deltas, row);
    INFO("empty (−1) and back-face (−2) pixels add nothing; the row is accumulated into, not overwritten");
    CHECK(row[0] == doctest::Approx(10.5));
    CHECK(row[1] == 20);
    CHECK(row[2] == doctest::Approx(30.311));
  }

  TEST_CASE("the row accumulation refuses items and deltas of different lengths and an item past the row" *
            doctest::description("task=5")) {
    // Contract of accumulate_face (hemicube_deltas.hpp): one item and one delta
    // per pixel; every item ≥ 0 an index of the row. A face is a span, not a
    // pointer and a count, so a length that disagrees can be seen, and refused.
    const std::vector<std::int32_t> items{0, 1, 1};
    const std::vector<double> deltas{0.25, 0.5};  // one delta short
    std::vector<double> row{1.0, 2.0};
    CHECK_THROWS_AS(accumulate_face(items, deltas, row), std::invalid_argument);
    // The other way round: one item short of the deltas (a face's items cut short).
    const std::vector<std::int32_t> short_items{0, 1};
    const std::vector<double> three{0.25, 0.5, 0.125};
    CHECK_THROWS_AS(accumulate_face(short_items, three, row), std::invalid_argument);
    const std::vector<std::int32_t> past{0, 2};  // item 2 of a row of two patches
    const std::vector<double> two{0.25, 0.5};
    CHECK_THROWS_AS(accumulate_face(past, two, row), std::invalid_argument);
    INFO("a face of two pixels whose lengths agree and whose items fit is accumulated");
    const std::vector<std::int32_t> fine{1, -1};
    accumulate_face(fine, two, row);
    CHECK(row[1] == doctest::Approx(2.25));
  }

  TEST_CASE("bad resolutions are refused" * doctest::description("task=3,4")) {
    CHECK(make_hemicube_deltas(4).resolution == 4);
    CHECK_THROWS_AS(make_hemicube_deltas(3), std::invalid_argument);
    CHECK_THROWS_AS(make_hemicube_deltas(0), std::invalid_argument);
    CHECK_THROWS_AS(make_hemicube_deltas(-8), std::invalid_argument);
    CHECK_THROWS_AS(Hemicube(7), std::invalid_argument);
    const std::vector<Patch> patches{receiver_at_origin(), ceiling_rect(-1, 1, -1, 1, 1)};
    const Hemicube hemicube(8);
    HemicubeBuffers buffers;
    std::vector<double> row(2);
    CHECK_THROWS_AS(hemicube.form_factor_row(patches, 2, row, buffers), std::invalid_argument);
    INFO("a row must hold one value per patch: one too few is refused, not written past");
    CHECK_THROWS_AS(hemicube.form_factor_row(patches, 0, std::span<double>(row).first(1), buffers),
                    std::invalid_argument);
  }

  TEST_CASE("a parallel square aligned with the pixels is exact (B-3)" * doctest::description("task=3,4,5")) {
    // Resolution 10: pixel edges at −1, −0.8, …, 1. A square of half side 0.6 at height 1
    // projects exactly onto pixel edges, so the exact deltas give the exact factor.
    const std::vector<Patch> patches{receiver_at_origin(), ceiling_rect(-0.6, 0.6, -0.6, 0.6, 1)};
    const auto row = row_of(patches, 10);
    INFO("four B-3 corners of 0.6 × 0.6 at height 1");
    CHECK(row[0] == 0);
    CHECK(row[1] == doctest::Approx(4 * howell_b3(0.6, 0.6, 1)).epsilon(1e-12));
  }

  TEST_CASE("a perpendicular wall aligned with the pixels is exact (B-4)" *
            doctest::description("task=3,4,5")) {
    // The wall x = 1, |y| ≤ 0.6, 0 ≤ z ≤ 0.4 covers whole pixels of the +x side face.
    const std::vector<Patch> patches{receiver_at_origin(), wall_rect(1, -0.6, 0.6, 0, 0.4)};
    const auto row = row_of(patches, 10);
    INFO("two B-4 rectangles of height 0.4, width 0.6 at distance 1");
    CHECK(row[1] == doctest::Approx(2 * howell_b4(0.4, 0.6, 1)).epsilon(1e-12));
  }

  TEST_CASE("a closed cube: every row sums to one, to round-off" * doctest::description("task=3,4,5")) {
    // Every direction above each patch hits exactly one other patch, so Σ_j F_ij = 1
    // (erratum 5 of docs/errata.md). With exact deltas, any pixel drawn twice or missed by the fill rule
    // would show as an error of at least one delta (> 1e-5 at resolution 24).
    const auto cube = closed_cube(3);
    for (bool rotate : {false, true}) {
      const FormFactorMatrix f = hemicube_form_factors(cube, 24, rotate, 7);
      REQUIRE(f.size() == cube.size());
      for (std::size_t i = 0; i < f.size(); ++i) {
        INFO("row " << i << (rotate ? " (random rotation)" : ""));
        CHECK(f(i, i) == 0);
        CHECK(f.row_sum(i) == doctest::Approx(1.0).epsilon(1e-12));
      }
    }
  }

  TEST_CASE("hard case: a floating block whose silhouette edges pass exactly through pixel centres" *
            doctest::description("task=3,4,5")) {
    // A closed room with a block inside: every row still sums to one. From the floor patch
    // centred at (0.375, 0.125, 0) the top face's pixel centre (−0.1875, 0.5625) looks exactly
    // along the block's vertical edge x = 0.3, y = 0.35, where a front face and a back face
    // meet at the same depth: the front face must win, or the pixel would count for nobody.
    std::vector<Patch> scene = closed_cube(4);
    const Point3 lo(0.3, 0.35, 0.25), hi(0.65, 0.7, 0.6);
    auto corner = [&](int x, int y, int z) {
      return Point3(x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z);
    };
    // Outward faces, counter-clockwise seen from outside.
    const int faces[6][4][3] = {
        {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
        {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}};
    for (const auto& f : faces) {
      std::vector<Point3> v;
      for (const auto& c : f) v.push_back(corner(c[0], c[1], c[2]));
      scene.push_back(make_patch(v));
      INFO("block face normals point away from the block's centre");
      REQUIRE(dot(scene.back().normal, scene.back().centroid - 0.5 * (lo + hi)) > 0);
    }
    const FormFactorMatrix f = hemicube_form_factors(scene, 16);
    for (std::size_t i = 0; i < f.size(); ++i) {
      INFO("row " << i);
      CHECK(f.row_sum(i) == doctest::Approx(1.0).epsilon(1e-12));
    }
  }

  TEST_CASE("a tilted quad anywhere above the patch converges to Lambert's contour formula" *
            doctest::description("task=3,4,5")) {
    const std::vector<Point3> quad{{0.3, -0.2, 0.5}, {1.1, 0.1, 0.9}, {0.9, 0.9, 1.3}, {0.1, 0.6, 0.9}};
    // make_patch takes the vertices counter-clockwise seen from the front; face the origin.
    Patch target = make_patch(quad);
    if (dot(target.normal, target.centroid) > 0) target = make_patch({quad[3], quad[2], quad[1], quad[0]});
    const std::vector<Patch> patches{receiver_at_origin(), target};
    const double exact = lambert_contour(Point3(0), Vec3(0, 0, 1), quad);
    for (int res : {64, 256}) {
      const auto row = row_of(patches, res, 0, 0.3);
      // Only pixels cut by the outline can be wrong: ≈ 3 (perimeter/pixel) pixels of ≤ (2/res)²/π each.
      const double bound = 3.0 * res * 4.0 / (res * res * kPi);
      INFO("resolution " << res << ": hemicube " << row[1] << ", Lambert " << exact);
      CHECK(std::abs(row[1] - exact) < bound);
    }
  }

  TEST_CASE("hard case: a patch seen edge-on gets nothing" * doctest::description("task=3,4,5")) {
    // The plane y = 0 contains the hemicube's centre: the patch projects to a line.
    const std::vector<Patch> patches{receiver_at_origin(),
                                     make_patch({{0.5, 0, 0.2}, {1.5, 0, 0.2}, {1.5, 0, 1}, {0.5, 0, 1}}),
                                     ceiling_rect(-1.2, 1.2, -1.2, 1.2, 2)};
    const auto row = row_of(patches, 10);
    CHECK_MESSAGE(row[1] == 0, "an edge-on patch subtends no solid angle");
    CHECK(row[2] == doctest::Approx(4 * howell_b3(1.2, 1.2, 2)).epsilon(1e-12));
  }

  TEST_CASE("hard case: a patch crossing the base plane counts only its part above" *
            doctest::description("task=3,4,5")) {
    // The wall reaches 0.5 below the patch's plane; the half face is clipped at z = 0.
    const std::vector<Patch> patches{receiver_at_origin(), wall_rect(1, -0.6, 0.6, -0.5, 0.4)};
    const auto row = row_of(patches, 10);
    INFO("only 0 ≤ z ≤ 0.4 is visible: two B-4 rectangles of height 0.4");
    CHECK(row[1] == doctest::Approx(2 * howell_b4(0.4, 0.6, 1)).epsilon(1e-12));
  }

  TEST_CASE("hard case: adjacent patches sharing an edge with the receiver" *
            doctest::description("task=3,4,5")) {
    // Receiver [−½, ½]² on the floor; a coplanar neighbour, and a wall rising from its edge x = ½.
    const std::vector<Patch> patches{
        receiver_at_origin(0.5), make_patch({{0.5, -0.5, 0}, {1.5, -0.5, 0}, {1.5, 0.5, 0}, {0.5, 0.5, 0}}),
        wall_rect(0.5, -0.5, 0.5, 0, 1)};
    const auto row = row_of(patches, 200);
    CHECK_MESSAGE(row[1] == 0, "a coplanar neighbour lies in the base plane: invisible");
    // From the centroid: two B-4 rectangles of height 1, width ½ at distance ½.
    const double point_value = 2 * howell_b4(1, 0.5, 0.5);
    // The area-to-area factor of two unit squares at right angles sharing an edge, Howell C-14 with
    // W = w/l = 1 and H = h/l = 1 (published as 0.20004); the hemicube measures the centroid's factor
    // instead (point sampling).
    const auto howell_c14 = [](double W, double H) {
      const double s = std::sqrt(H * H + W * W);
      const double a = (1 + W * W) * (1 + H * H) / (1 + W * W + H * H);
      const double b = W * W * (1 + W * W + H * H) / ((1 + W * W) * (W * W + H * H));
      const double c = H * H * (1 + H * H + W * W) / ((1 + H * H) * (H * H + W * W));
      return (W * std::atan(1 / W) + H * std::atan(1 / H) - s * std::atan(1 / s) +
              0.25 * (std::log(a) + W * W * std::log(b) + H * H * std::log(c))) /
             (std::numbers::pi * W);
    };
    const double area_value = howell_c14(1, 1);
    CHECK_MESSAGE(std::abs(area_value - 0.20004) < 0.5e-5,
                  "C-14 as transcribed must give the table's 0.20004");
    INFO("hemicube " << row[2] << ", centroid's exact factor " << point_value << ", area-averaged "
                     << area_value);
    CHECK(std::abs(row[2] - point_value) < 3.0 * 200 * 4.0 / (200.0 * 200 * kPi));
    CHECK(std::abs(row[2] - area_value) > 0.005);
  }

  TEST_CASE("hard case: a patch behind another gets nothing" * doctest::description("task=3,4,5")) {
    const std::vector<Patch> patches{receiver_at_origin(), ceiling_rect(-0.2, 0.2, -0.2, 0.2, 2),
                                     ceiling_rect(-0.6, 0.6, -0.6, 0.6, 1)};
    const auto row = row_of(patches, 10);
    CHECK_MESSAGE(row[1] == 0, "the small square at height 2 is hidden by the big one at height 1");
    CHECK(row[2] == doctest::Approx(4 * howell_b3(0.6, 0.6, 1)).epsilon(1e-12));
  }

  TEST_CASE("hard case: a patch seen from behind hides what is behind it and receives nothing" *
            doctest::description("task=3,4,5")) {
    // Positive controls: a row of zeros would pass both checks at the end.
    // Alone, the small square at height 2 projects onto [−0.1, 0.1]² of the top
    // face, exactly 2 × 2 pixels at resolution 20, whose exact deltas add up to
    // the square's whole form factor (Lambert's formula).
    const Point3 centre(0.0);
    const Vec3 up(0, 0, 1);
    const auto alone = row_of({receiver_at_origin(), ceiling_rect(-0.2, 0.2, -0.2, 0.2, 2)}, 20);
    const double small_exact =
        lambert_contour(centre, up, {{-0.2, -0.2, 2}, {0.2, -0.2, 2}, {0.2, 0.2, 2}, {-0.2, 0.2, 2}});
    REQUIRE_MESSAGE(alone[1] == doctest::Approx(small_exact).epsilon(1e-12),
                    "with nothing in front, the small square receives its whole form factor");
    // Turned towards the receiver, the big square at height 1 (±0.6: pixel edges at resolution 10)
    // hides the small one and receives its whole form factor.
    const auto facing = row_of(
        {receiver_at_origin(), ceiling_rect(-0.2, 0.2, -0.2, 0.2, 2), ceiling_rect(-0.6, 0.6, -0.6, 0.6, 1)},
        10);
    const double big_exact =
        lambert_contour(centre, up, {{-0.6, -0.6, 1}, {0.6, -0.6, 1}, {0.6, 0.6, 1}, {-0.6, 0.6, 1}});
    CHECK(facing[1] == 0);
    CHECK(facing[2] == doctest::Approx(big_exact).epsilon(1e-12));
    // The same big square, but facing up (away from the receiver).
    const std::vector<Patch> patches{
        receiver_at_origin(), ceiling_rect(-0.2, 0.2, -0.2, 0.2, 2),
        make_patch({{-0.6, -0.6, 1}, {0.6, -0.6, 1}, {0.6, 0.6, 1}, {-0.6, 0.6, 1}})};
    const auto row = row_of(patches, 10);
    CHECK(row[1] == 0);
    CHECK_MESSAGE(row[2] == 0, "cos θ_j < 0: energy reaching the back of a one-sided patch is not F_ij");
  }

  TEST_CASE("hard case: a tiny distant patch aliases: all of a pixel or nothing" *
            doctest::description("task=3,4,5")) {
    // A square 0.02 wide at height 1 covers 1/25 of a pixel at resolution 20 (pixel 0.1 wide).
    const int res = 20;
    const HemicubeDeltas d = make_hemicube_deltas(res);
    // Centred on a pixel centre (x = y = 0.05): it gets that whole pixel's delta.
    const auto hit = row_of({receiver_at_origin(), ceiling_rect(0.04, 0.06, 0.04, 0.06, 1)}, res);
    CHECK(hit[1] == doctest::Approx(d.top[static_cast<std::size_t>(res / 2) * res + res / 2]).epsilon(1e-14));
    // Between pixel centres (x = y = 0.1): it is missed.
    const auto miss = row_of({receiver_at_origin(), ceiling_rect(0.09, 0.11, 0.09, 0.11, 1)}, res);
    CHECK(miss[1] == 0);
    const double exact = lambert_contour(
        Point3(0), Vec3(0, 0, 1), {{0.04, 0.04, 1}, {0.06, 0.04, 1}, {0.06, 0.06, 1}, {0.04, 0.06, 1}});
    INFO("exact " << exact << ", hemicube " << hit[1] << ": about 25 times too much");
    CHECK(hit[1] > 20 * exact);
  }

  TEST_CASE("reflectance and emission play no part in form factors" * doctest::description("task=3,4,5")) {
    std::vector<Patch> patches{receiver_at_origin(), ceiling_rect(-0.5, 0.7, -0.3, 0.6, 1.2)};
    const auto plain = row_of(patches, 32);
    patches[1].reflectance = Color(0.99);
    patches[1].emission = Color(5.0);
    patches[0].reflectance = Color(0.01);
    const auto coloured = row_of(patches, 32);
    CHECK(plain[1] > 0);
    CHECK(coloured[1] == plain[1]);
  }

  TEST_CASE("the parallel matrix equals the rows one by one" * doctest::description("task=3,4,5")) {
    const auto cube = closed_cube(2);
    const FormFactorMatrix f = hemicube_form_factors(cube, 16, true, 3);
    const FormFactorMatrix g = hemicube_form_factors(cube, 16, true, 3);
    const Hemicube hemicube(16);
    HemicubeBuffers buffers;
    std::vector<double> row(cube.size());
    hemicube.form_factor_row(cube, 5, row, buffers);
    const FormFactorMatrix unrotated = hemicube_form_factors(cube, 16);
    // Inside the closed cube every pixel sees some patch and the exact deltas
    // sum to 1, so each row sums to 1 (erratum 5 of docs/errata.md): an all-zero row, equal in
    // every version, fails here.
    double row_sum = 0, rotated_sum = 0;
    for (std::size_t j = 0; j < cube.size(); ++j) row_sum += row[j], rotated_sum += f(5, j);
    CHECK_MESSAGE(row_sum == doctest::Approx(1.0).epsilon(1e-12), "a closed cube: Σ_j F_5j = 1 (erratum 5)");
    CHECK_MESSAGE(rotated_sum == doctest::Approx(1.0).epsilon(1e-12),
                  "rotating the hemicube keeps Σ_j F_5j = 1");
    for (std::size_t j = 0; j < cube.size(); ++j) {
      CHECK(unrotated(5, j) == row[j]);
      CHECK(f(5, j) == g(5, j));  // the same seed gives the same matrix
    }
  }
}
