// Lesson 03, outside grading: huge and tiny coordinates (the
// "far from the origin / tiny scene" hard case of docs/architecture.md) for triangles and convex
// polygons. A square split along its diagonal, and a convex hexagon, are
// placed 1e8 away from the origin and shrunk to 1e−8: hits, barycentrics,
// the shared diagonal and the inside test behave as at unit size.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "illum/geometry/convex.hpp"
#include "illum/geometry/triangle.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

Point3 at(const Point3& o, double k, double u, double v) { return Point3(o.x + k * u, o.y + k * v, o.z); }

// The square [0,1]² at scale k from corner o, split along (0,0)–(1,1).
std::vector<Triangle> split_square(const Point3& o, double k) {
  return {Triangle(at(o, k, 0, 0), at(o, k, 1, 0), at(o, k, 1, 1)),
          Triangle(at(o, k, 0, 0), at(o, k, 1, 1), at(o, k, 0, 1))};
}

// A ray from 3k above and k/2 to the side, aimed at the point (u, v).
Ray aimed(const Point3& o, double k, double u, double v) {
  const Point3 target = at(o, k, u, v);
  const Point3 origin(target.x - 0.5 * k, target.y + 0.25 * k, target.z + 3 * k);
  return Ray::toward(origin, target - origin);
}

void check_square(const Point3& o, double k) {
  const std::vector<Triangle> pair = split_square(o, k);
  INFO("scale " << k << ", offset (" << o.x << ", " << o.y << ", " << o.z << ")");
  // (0.75, 0.25) lies in the first triangle a = (0,0), b = (1,0), c = (1,1):
  // (u, v) = λb·(1,0) + λc·(1,1) gives λc = v = 0.25, λb = u − v = 0.5, λa = 0.25.
  const std::optional<TriangleHit> hit = intersect(aimed(o, k, 0.75, 0.25), pair[0]);
  REQUIRE_MESSAGE(hit.has_value(), "(0.75, 0.25) is inside the lower-right triangle");
  // The origin is √(0.5² + 0.25² + 3²)·k away; s carries a few ulps of the coordinates.
  const double distance = k * std::sqrt(0.25 + 0.0625 + 9.0);
  const double coordinate_ulp = std::max(std::abs(o.x), std::max(std::abs(o.y), std::abs(o.z))) * 0x1p-52;
  CHECK_MESSAGE(std::abs(hit->s - distance) <= 1e-12 * distance + 8 * coordinate_ulp,
                "s is the distance from the origin to the aimed-at point");
  CHECK_MESSAGE(std::abs(hit->barycentric.x - 0.25) <= 1e-9, "λa = 1 − u = 0.25");
  CHECK_MESSAGE(std::abs(hit->barycentric.y - 0.5) <= 1e-9, "λb = u − v = 0.5");
  CHECK_MESSAGE(std::abs(hit->barycentric.z - 0.25) <= 1e-9, "λc = v = 0.25");
  CHECK_MESSAGE(!intersect(aimed(o, k, 0.75, 0.25), pair[1]).has_value(), "the other triangle is beside it");
  CHECK_MESSAGE(!intersect(aimed(o, k, 1.0 + 1e-6, 0.5), pair[0]).has_value(),
                "1e−6 (relative) beyond the edge u = 1 is outside at any offset or scale");
  CHECK_MESSAGE(intersect(aimed(o, k, 1.0 - 1e-6, 0.5), pair[0]).has_value(),
                "1e−6 (relative) inside the edge u = 1 is inside at any offset or scale");
  for (double t : {0.125, 0.5, 0.625}) {
    const Ray ray = aimed(o, k, t, t);
    const int count = (intersect(ray, pair[0]) ? 1 : 0) + (intersect(ray, pair[1]) ? 1 : 0);
    INFO("aimed at the shared diagonal at (" << t << ", " << t << ")");
    CHECK_MESSAGE(count == 1,
                  "a point on the shared edge belongs to exactly one triangle: no crack, no double");
  }
}

// A convex hexagon (a regular hexagon squashed to rational vertices) at scale k.
ConvexPolygon hexagon(const Point3& o, double k) {
  const double uv[6][2] = {{1, 0}, {3, 0}, {4, 2}, {3, 4}, {1, 4}, {0, 2}};
  std::vector<Point3> loop;
  for (const auto& p : uv) loop.push_back(at(o, k, p[0], p[1]));
  return ConvexPolygon(Polygon(loop));
}

void check_hexagon(const Point3& o, double k) {
  INFO("scale " << k << ", offset (" << o.x << ", " << o.y << ", " << o.z << ")");
  const ConvexPolygon hex = hexagon(o, k);
  CHECK(hex.orientation() == 1);
  const auto q = [&](double u, double v) { return hex.polygon().project(at(o, k, u, v)); };
  CHECK_MESSAGE(inside_convex(hex, q(2, 2)), "the centre");
  // The edge from (3, 0) to (4, 2) is the line 2u − v = 6: at v = 1, u = 3.5.
  CHECK_MESSAGE(inside_convex(hex, q(3.5 - 1e-6, 1)), "1e−6 inside the slanted edge 2u − v = 6");
  CHECK_MESSAGE(!inside_convex(hex, q(3.5 + 1e-6, 1)), "1e−6 outside the slanted edge 2u − v = 6");
  CHECK_MESSAGE(!inside_convex(hex, q(0.5, 0.5)), "beyond the corner edge (0, 2)–(1, 0)");
  const std::vector<Point3> dart{at(o, k, 0, 0), at(o, k, 4, 0), at(o, k, 1, 1), at(o, k, 0, 4)};
  CHECK_MESSAGE(!is_convex(Polygon(dart)), "the reflex vertex (1, 1) turns the other way at any scale");
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("hard case: triangles offset by 1e8 keep their hits, barycentrics and shared edge") {
    check_square(Point3(1e8, -1e8, 1e8), 1.0);
  }

  TEST_CASE("hard case: triangles scaled by 1e-8 keep their hits, barycentrics and shared edge") {
    check_square(Point3(0.0), 1e-8);
    check_square(Point3(2e-8, 3e-8, -1e-8), 1e-8);
  }

  TEST_CASE("hard case: a convex polygon offset by 1e8 or scaled by 1e-8 keeps its inside test") {
    check_hexagon(Point3(1e8, 1e8, -1e8), 1.0);
    check_hexagon(Point3(0.0), 1e-8);
  }
}
