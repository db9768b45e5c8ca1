// Lesson 02, outside grading: huge and tiny coordinates (the
// "far from the origin / tiny scene" hard case of docs/architecture.md). The same non-convex polygon
// is placed 1e8 away from the origin and shrunk to 1e−8; a correct ray–polygon
// test decides every point as it does at unit size, because nothing in it
// depends on where the polygon is or how big it is (no absolute epsilon).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "illum/geometry/parity.hpp"
#include "illum/geometry/polygon.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

// The L-shaped hexagon [0,2]×[0,1] ∪ [0,1]×[0,2] in local coordinates (u, v):
// non-convex, with its reflex vertex at (1, 1).
const double ell_uv[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

// Local (u, v) at scale k from corner o, either in the horizontal plane
// (u, v, 0) or in the tilted plane (u, v, u): x − z is then exactly constant
// (both coordinates get the same rounded value), so the polygon is exactly
// planar even where k·u is not representable.
Point3 place(const Point3& o, double k, double u, double v, bool tilted) {
  return Point3(o.x + k * u, o.y + k * v, o.z + (tilted ? k * u : 0.0));
}

Polygon ell(const Point3& o, double k, bool tilted) {
  std::vector<Point3> loop;
  for (const auto& uv : ell_uv) loop.push_back(place(o, k, uv[0], uv[1], tilted));
  return Polygon(loop);
}

struct Probe {
  double u, v;
  bool inside;
  const char* why;
};

// Points at a relative distance of 1e−6 from an edge: at 1e8 the coordinates
// are rounded to ulp(1e8) = 2⁻²⁶ ≈ 1.5e−8, at 1e−8 to about 1e−24, both far
// below the margin, so the expected side is certain.
const Probe probes[] = {
    {0.5, 0.5, true, "the corner square of the L"},
    {1.5, 0.5, true, "the lower arm"},
    {0.5, 1.5, true, "the upper arm"},
    {1.0 - 1e-6, 1.0 + 1e-6, true, "just left of the reflex vertex's vertical edge"},
    {1.0 + 1e-6, 1.0 - 1e-6, true, "just below the reflex vertex's horizontal edge"},
    {1.0 + 1e-6, 1.0 + 1e-6, false, "just inside the notch of the L"},
    {1.5, 1.5, false, "the middle of the notch"},
    {2.0 + 1e-6, 0.5, false, "just right of the lower arm"},
    {0.5, -1e-6, false, "just below the bottom edge"},
    {-1e-6, 1.5, false, "just left of the left edge"},
};

// A ray dropped vertically from height 5k above the point (u, v) of the
// polygon: in both planes the vertical line meets the plane at that point,
// so the exact hit is at s = 5k.
void check_probes(const Point3& o, double k, bool tilted, double s_tolerance) {
  const Polygon polygon = ell(o, k, tilted);
  for (const Probe& p : probes) {
    const Point3 target = place(o, k, p.u, p.v, tilted);
    const Ray ray(Point3(target.x, target.y, target.z + 5 * k), Vec3(0, 0, -1));
    INFO("scale " << k << ", offset " << o.x << (tilted ? ", tilted plane" : ", plane z = const")
                  << ": (u, v) = (" << p.u << ", " << p.v << "), " << p.why);
    const std::optional<PolygonHit> hit = intersect(ray, polygon);
    CHECK_MESSAGE(hit.has_value() == p.inside,
                  "the side of a point 1e−6 (relative) from an edge cannot depend on offset or scale");
    if (hit && p.inside)
      CHECK_MESSAGE(std::abs(hit->s - 5 * k) <= s_tolerance,
                    "the vertical drop of 5k meets the plane at the target point: s = 5k");
  }
}

}  // namespace

TEST_SUITE("stability") {
  TEST_CASE("hard case: a non-convex polygon offset by 1e8 is hit and missed as at the origin") {
    // s = −(D + N·P0)/(N·ω) with D ≈ −N·o: the cancellation of two numbers
    // near 1e8 leaves an absolute error of a few ulp(1e8) ≈ 1.5e−8 in s.
    const double ulp = std::ldexp(1.0, -26);
    check_probes(Point3(1e8, 1e8, 1e8), 1.0, false, 4 * ulp);
    check_probes(Point3(-3e8, 2e8, 1e8), 1.0, true, 8 * ulp);
  }

  TEST_CASE("hard case: a non-convex polygon scaled by 1e-8 is hit and missed as at unit size") {
    // Every quantity scales with k: s = 5e−8 to a few ulps, relative 1e−12.
    check_probes(Point3(0.0), 1e-8, false, 5e-8 * 1e-12);
    check_probes(Point3(3e-8, -2e-8, 1e-8), 1e-8, true, 5e-8 * 1e-12);
  }
}
