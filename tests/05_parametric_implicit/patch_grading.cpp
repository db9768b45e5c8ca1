// Lesson 05 grading tests: rays against Bézier patches by two planes and
// Newton in (u, v). Expected hits come from hand calculations, from the
// bilinear patch's closed-form quadratic and from Bernstein sums written here.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/patch_newton.hpp"
#include "support/string_makers.hpp"

using namespace illum;

namespace {

// S(u, v) = (u, v, uv): the saddle with corners (0,0,0), (1,0,0), (0,1,0), (1,1,1).
BezierPatch saddle() {
  return BezierPatch::bilinear(Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(1, 1, 1));
}

double binomial3(int i) { return i == 0 || i == 3 ? 1.0 : 3.0; }
double bernstein3(int i, double t) { return binomial3(i) * std::pow(t, i) * std::pow(1.0 - t, 3 - i); }
double bernstein2(int i, double t) {
  return (i == 1 ? 2.0 : 1.0) * std::pow(t, i) * std::pow(1.0 - t, 2 - i);
}

// A bicubic height field: P_ij = (i/3, j/3, h_ij). Bernstein polynomials
// reproduce linear functions, so x = u and y = v exactly and S = (u, v, h(u, v)).
struct HeightField {
  double h[4][4];  // h[i][j]
  BezierPatch patch() const {
    std::vector<Point3> points;
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 3; ++i) points.emplace_back(i / 3.0, j / 3.0, h[i][j]);
    return BezierPatch(3, 3, points);
  }
  double height(double u, double v) const {
    double z = 0.0;
    for (int i = 0; i <= 3; ++i)
      for (int j = 0; j <= 3; ++j) z += bernstein3(i, u) * bernstein3(j, v) * h[i][j];
    return z;
  }
  // ∂h/∂u = 3 Σ (h_{i+1,j} − h_ij) B_i²(u) B_j³(v), and likewise in v.
  double height_du(double u, double v) const {
    double d = 0.0;
    for (int i = 0; i <= 2; ++i)
      for (int j = 0; j <= 3; ++j) d += 3.0 * (h[i + 1][j] - h[i][j]) * bernstein2(i, u) * bernstein3(j, v);
    return d;
  }
  double height_dv(double u, double v) const {
    double d = 0.0;
    for (int i = 0; i <= 3; ++i)
      for (int j = 0; j <= 2; ++j) d += 3.0 * (h[i][j + 1] - h[i][j]) * bernstein3(i, u) * bernstein2(j, v);
    return d;
  }
};

const HeightField hump{
    {{0.0, 0.0, 0.0, 0.0}, {0.0, 1.5, 1.5, 0.0}, {0.0, 1.5, 1.5, 0.0}, {0.0, 0.0, 0.0, 0.0}}};
const HeightField wavy{
    {{0.1, 0.3, -0.2, 0.0}, {0.4, 0.9, 0.2, -0.3}, {-0.1, 0.5, 1.1, 0.2}, {0.0, -0.4, 0.3, 0.6}}};

struct Exact {
  double s, u, v;
};

// Ray–bilinear patch in closed form, solved here independently in long double:
// S = P00 + u e + v f + uv g. Two planes through the ray, with normals
// m₁, m₂ ⟂ ω chosen here, give a_k + b_k u + c_k v + g_k uv = 0; eliminating u
// leaves A v² + B v + C = 0. The nearest root with u, v ∈ [0, 1], s > 0 wins.
std::optional<Exact> bilinear_exact(const Ray& ray, Point3 p00, Point3 p10, Point3 p01, Point3 p11) {
  using L = long double;
  const Vec3 w = ray.direction;
  const Vec3 m1 = normalize(cross(w, Vec3(0.3, 0.9, 0.1)));
  const Vec3 m2 = normalize(cross(w, m1));
  const Vec3 e = p10 - p00, f = p01 - p00, g = p11 - p10 - p01 + p00;
  auto coeffs = [&](const Vec3& m, L& a, L& b, L& c, L& d) {
    a = L(m.x) * (L(p00.x) - L(ray.origin.x)) + L(m.y) * (L(p00.y) - L(ray.origin.y)) +
        L(m.z) * (L(p00.z) - L(ray.origin.z));
    b = L(m.x) * e.x + L(m.y) * e.y + L(m.z) * e.z;
    c = L(m.x) * f.x + L(m.y) * f.y + L(m.z) * f.z;
    d = L(m.x) * g.x + L(m.y) * g.y + L(m.z) * g.z;
  };
  L a1, b1, c1, g1, a2, b2, c2, g2;
  coeffs(m1, a1, b1, c1, g1);
  coeffs(m2, a2, b2, c2, g2);
  // (a₂ + c₂v)(b₁ + g₁v) − (b₂ + g₂v)(a₁ + c₁v) = 0
  const L A = c2 * g1 - g2 * c1, B = a2 * g1 + c2 * b1 - b2 * c1 - g2 * a1, C = a2 * b1 - b2 * a1;
  std::vector<L> vs;
  if (std::fabs(A) < 1e-18L) {
    vs.push_back(-C / B);
  } else {
    const L disc = B * B - 4 * A * C;
    if (disc < 0) return std::nullopt;
    vs.push_back((-B - std::sqrt(disc)) / (2 * A));
    vs.push_back((-B + std::sqrt(disc)) / (2 * A));
  }
  std::optional<Exact> best;
  for (L v : vs) {
    const L den1 = b1 + g1 * v, den2 = b2 + g2 * v;
    const L u = std::fabs(den1) > std::fabs(den2) ? -(a1 + c1 * v) / den1 : -(a2 + c2 * v) / den2;
    if (u < 0 || u > 1 || v < 0 || v > 1) continue;
    L s = 0;
    for (int k = 0; k < 3; ++k) {
      const L pk = L(p00[k]) + u * e[k] + v * f[k] + u * v * g[k];
      s += (pk - L(ray.origin[k])) * L(w[k]);
    }
    if (s > 0 && (!best || s < best->s))
      best = Exact{static_cast<double>(s), static_cast<double>(u), static_cast<double>(v)};
  }
  return best;
}

}  // namespace

TEST_SUITE("lesson05") {
  TEST_CASE("ray_planes: two orthonormal planes that both contain the ray" * doctest::description("task=5")) {
    const Ray rays[] = {Ray(Point3(1, 2, 3), Vec3(1, 0, 0)), Ray(Point3(-4, 0.5, 2), Vec3(0, 0, -1)),
                        Ray::toward(Point3(0.3, -7, 1e3), Vec3(1, 1, 1)),
                        Ray::toward(Point3(2, 2, 2), Vec3(-0.2, 0.9, 0.01))};
    for (const Ray& ray : rays) {
      const RayPlanes p = ray_planes(ray);
      INFO("ω = (" << ray.direction.x << ", " << ray.direction.y << ", " << ray.direction.z << ")");
      CHECK_MESSAGE(std::abs(length(p.n1) - 1.0) <= 1e-15, "N₁ is a unit normal: F₁ is a distance");
      CHECK_MESSAGE(std::abs(length(p.n2) - 1.0) <= 1e-15, "N₂ is a unit normal: F₂ is a distance");
      CHECK_MESSAGE(std::abs(dot(p.n1, ray.direction)) <= 1e-15, "N₁ ⟂ ω: π₁ is parallel to the ray");
      CHECK_MESSAGE(std::abs(dot(p.n2, ray.direction)) <= 1e-15, "N₂ ⟂ ω: π₂ is parallel to the ray");
      CHECK_MESSAGE(std::abs(dot(p.n1, p.n2)) <= 1e-15, "π₁ ⟂ π₂: the best-conditioned pair of planes");
      for (double s : {0.0, 7.0}) {
        const Point3 q = ray.at(s);
        const double scale = 1.0 + length(q);
        CHECK_MESSAGE(std::abs(dot(p.n1, q) + p.d1) <= 1e-14 * scale, "every point of the ray lies on π₁");
        CHECK_MESSAGE(std::abs(dot(p.n2, q) + p.d2) <= 1e-14 * scale, "every point of the ray lies on π₂");
      }
    }
  }

  TEST_CASE("bilinear saddle: a vertical ray hits (a, b, ab) with normal (−b, −a, 1)" *
            doctest::description("task=5,6,7")) {
    // S = (u, v, uv), S_u = (1, 0, v), S_v = (0, 1, u), S_u × S_v = (−v, −u, 1).
    const Ray ray(Point3(0.3, 0.7, 5.0), Vec3(0.0, 0.0, -1.0));
    const std::optional<PatchHit> hit = intersect_patch(ray, saddle());
    REQUIRE_MESSAGE(hit, "the ray is above the patch's parameter square: it must hit");
    CHECK(hit->u == doctest::Approx(0.3).epsilon(1e-12));
    CHECK(hit->v == doctest::Approx(0.7).epsilon(1e-12));
    CHECK_MESSAGE(hit->s == doctest::Approx(5.0 - 0.21).epsilon(1e-12), "z = uv = 0.21, s = 5 − 0.21");
    const Vec3 expected = normalize(Vec3(-0.7, -0.3, 1.0));
    CHECK_MESSAGE(length(hit->normal - expected) <= 1e-12, "the normal is S_u × S_v normalised");
    CHECK(length(hit->point - Point3(0.3, 0.7, 0.21)) <= 1e-12);
  }

  TEST_CASE("bilinear patch: a slanted ray agrees with the closed-form quadratic" *
            doctest::description("task=5,6,7")) {
    const Point3 p00(0, 0, 0), p10(2, 0, 0.5), p01(0, 2, -0.3), p11(2.2, 2.1, 1.4);
    const BezierPatch patch = BezierPatch::bilinear(p00, p10, p01, p11);
    const Ray rays[] = {Ray::toward(Point3(-1, 0.5, 3), Vec3(2.2, 0.6, -2.8)),
                        Ray::toward(Point3(3, 3, -2), Vec3(-1.4, -1.9, 2.2)),
                        Ray::toward(Point3(1, -2, 1), Vec3(0.1, 1, -0.1))};
    for (const Ray& ray : rays) {
      const std::optional<Exact> exact = bilinear_exact(ray, p00, p10, p01, p11);
      REQUIRE_MESSAGE(exact, "the test rays are aimed at the patch");
      const std::optional<PatchHit> hit = intersect_patch(ray, patch);
      REQUIRE(hit);
      INFO("exact s = " << exact->s << ", u = " << exact->u << ", v = " << exact->v);
      CHECK_MESSAGE(std::abs(hit->s - exact->s) <= 1e-10, "Newton reaches the root of the quadratic");
      CHECK(std::abs(hit->u - exact->u) <= 1e-10);
      CHECK(std::abs(hit->v - exact->v) <= 1e-10);
    }
  }

  TEST_CASE("bicubic height field: a vertical ray hits z = h(u, v) from the Bernstein sum" *
            doctest::description("task=5,6,7")) {
    const BezierPatch patch = wavy.patch();
    const double u = 0.37, v = 0.61;
    const Ray ray(Point3(u, v, 10.0), Vec3(0.0, 0.0, -1.0));
    const std::optional<PatchHit> hit = intersect_patch(ray, patch);
    REQUIRE(hit);
    const double z = wavy.height(u, v);
    CHECK_MESSAGE(std::abs(hit->s - (10.0 - z)) <= 1e-11, "z = Σ B_i³(u) B_j³(v) h_ij");
    CHECK_MESSAGE(std::abs(hit->u - u) <= 1e-11, "x = u on a height field (linear precision)");
    CHECK(std::abs(hit->v - v) <= 1e-11);
    const Vec3 expected = normalize(Vec3(-wavy.height_du(u, v), -wavy.height_dv(u, v), 1.0));
    CHECK_MESSAGE(length(hit->normal - expected) <= 1e-9, "(1, 0, h_u) × (0, 1, h_v) = (−h_u, −h_v, 1)");
  }

  TEST_CASE("hard case: a ray that crosses a hump twice returns the nearer hit" *
            doctest::description("task=5,6,7")) {
    // The horizontal ray z = 0.4 along y = 0.5 enters the hump where h(x, ½)
    // rises through 0.4 and leaves where it falls back: the first crossing,
    // found here by bisection of h(x, ½) − 0.4 on [0, ½], is the answer.
    const BezierPatch patch = hump.patch();
    const Ray ray(Point3(-0.5, 0.5, 0.4), Vec3(1.0, 0.0, 0.0));
    REQUIRE(hump.height(0.0, 0.5) < 0.4);
    REQUIRE(hump.height(0.5, 0.5) > 0.4);
    REQUIRE(hump.height(1.0, 0.5) < 0.4);
    double a = 0.0, b = 0.5;
    for (int k = 0; k < 200; ++k) {
      const double m = 0.5 * (a + b);
      (hump.height(m, 0.5) < 0.4 ? a : b) = m;
    }
    const double x_first = 0.5 * (a + b);
    const std::optional<PatchHit> hit = intersect_patch(ray, patch);
    REQUIRE(hit);
    CHECK_MESSAGE(std::abs(hit->s - (x_first + 0.5)) <= 1e-10,
                  "two roots along the ray: the nearer one (rising side of the hump) is the hit");
    CHECK_MESSAGE(hit->u < 0.5, "the hit is on the near side of the hump");
  }

  TEST_CASE("hard case: a planar patch seen edge-on is not hit, a nearly edge-on ray is" *
            doctest::description("task=5,6,7")) {
    const BezierPatch flat =
        BezierPatch::bilinear(Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(1, 1, 0));
    // In the patch's plane: the line meets the patch in a segment, det J = ω·(S_u × S_v) = 0.
    const Ray in_plane(Point3(-1.0, 0.5, 0.0), Vec3(1.0, 0.0, 0.0));
    CHECK_MESSAGE(!intersect_patch(in_plane, flat), "an edge-on patch has no projected area: no hit, no NaN");
    const Ray above(Point3(-1.0, 0.5, 1e-3), Vec3(1.0, 0.0, 0.0));
    CHECK_MESSAGE(!intersect_patch(above, flat), "parallel to the plane and above it: no hit");
    // Nearly edge-on but piercing: from (−1, ½, 0.01) to (½, ½, 0).
    const Ray grazing = Ray::toward(Point3(-1.0, 0.5, 0.01), Vec3(1.5, 0.0, -0.01));
    const std::optional<PatchHit> hit = intersect_patch(grazing, flat);
    REQUIRE_MESSAGE(hit, "a grazing ray that crosses the plane inside the square hits");
    CHECK(std::abs(hit->s - std::hypot(1.5, 0.01)) <= 1e-10);
    CHECK(std::abs(hit->u - 0.5) <= 1e-10);
    CHECK(std::abs(hit->v - 0.5) <= 1e-10);
  }

  TEST_CASE("hard case: a patch with a collapsed edge (coincident corners) still has a unit normal" *
            doctest::description("task=5,6,7")) {
    // P00 = P10: the edge v = 0 is a single point. S = (uv, v, 0): S_u = (v, 0, 0)
    // vanishes on that edge, so S_u × S_v = (0, 0, v) is zero there.
    const BezierPatch triangle =
        BezierPatch::bilinear(Point3(0, 0, 0), Point3(0, 0, 0), Point3(0, 1, 0), Point3(1, 1, 0));
    const Ray ray(Point3(0.2, 0.6, 5.0), Vec3(0.0, 0.0, -1.0));
    const std::optional<PatchHit> hit = intersect_patch(ray, triangle);
    REQUIRE_MESSAGE(hit, "(0.2, 0.6) lies in the triangle x ≤ y, 0 ≤ y ≤ 1");
    CHECK(std::abs(hit->s - 5.0) <= 1e-12);
    CHECK_MESSAGE(std::abs(hit->u - 1.0 / 3.0) <= 1e-10, "x = uv: u = 0.2/0.6");
    CHECK(std::abs(hit->v - 0.6) <= 1e-10);
    CHECK(length(hit->normal - Vec3(0, 0, 1)) <= 1e-12);
    // Next to the collapsed corner the Jacobian is nearly singular.
    const Ray corner(Point3(1e-4, 2e-4, 5.0), Vec3(0.0, 0.0, -1.0));
    const std::optional<PatchHit> near_corner = intersect_patch(corner, triangle);
    REQUIRE(near_corner);
    CHECK_MESSAGE(std::abs(length(near_corner->normal) - 1.0) <= 1e-12, "the normal stays a unit vector");
    CHECK_MESSAGE(near_corner->normal.z == doctest::Approx(1.0), "the flat triangle faces +z");
  }

  TEST_CASE("intersect_patch: misses beside the patch and behind the origin" *
            doctest::description("task=5,6,7")) {
    // Positive control: straight down onto (0.5, 0.5), where z = uv = 0.25, so
    // s = 5 − 0.25 = 4.75. An intersector that always missed would pass the rest.
    const std::optional<PatchHit> hit = intersect_patch(Ray(Point3(0.5, 0.5, 5), Vec3(0, 0, -1)), saddle());
    REQUIRE_MESSAGE(hit, "(0.5, 0.5) is inside the parameter square: the ray hits the saddle");
    CHECK(std::abs(hit->s - 4.75) <= 1e-10);
    CHECK_MESSAGE(!intersect_patch(Ray(Point3(2, 2, 5), Vec3(0, 0, -1)), saddle()),
                  "(2, 2) is outside the square: the box test prunes the whole patch");
    CHECK_MESSAGE(!intersect_patch(Ray(Point3(0.5, 0.5, 5), Vec3(0, 0, 1)), saddle()),
                  "the patch lies behind the origin: s < 0 is not a hit");
    Ray limited(Point3(0.5, 0.5, 5), Vec3(0, 0, -1));
    limited.range = Interval(0.0, 4.0);
    CHECK_MESSAGE(!intersect_patch(limited, saddle()), "the hit at s = 4.75 lies beyond the range's end");
    limited.range = Interval(0.0, 5.0);
    CHECK_MESSAGE(intersect_patch(limited, saddle()),
                  "with the range [0, 5] the hit at s = 4.75 counts again");
  }

  TEST_CASE("patch_newton converges in a few steps and refuses bad input" *
            doctest::description("task=5,6,7")) {
    const Ray ray(Point3(0.3, 0.7, 5.0), Vec3(0.0, 0.0, -1.0));
    const RayPlanes planes = ray_planes(ray);
    const std::optional<PatchHit> hit = patch_newton(saddle(), ray, planes, Vec2(0.5, 0.5), 1e-14, 20);
    REQUIRE(hit);
    CHECK_MESSAGE(hit->iterations <= 4, "x = u and y = v are linear: Newton lands on (0.3, 0.7) in one step");
    CHECK(std::abs(hit->u - 0.3) <= 1e-14);
    CHECK(std::abs(hit->v - 0.7) <= 1e-14);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(patch_newton(saddle(), ray, planes, Vec2(nan, 0.5), 1e-12, 20), std::invalid_argument);
    CHECK_THROWS_AS(patch_newton(saddle(), ray, planes, Vec2(0.5, 0.5), 0.0, 20), std::invalid_argument);
    PatchOptions bad;
    bad.max_depth = -1;
    CHECK_THROWS_AS(intersect_patch(ray, saddle(), bad), std::invalid_argument);
    bad.max_depth = 4;
    bad.tolerance = nan;
    CHECK_THROWS_AS(intersect_patch(ray, saddle(), bad), std::invalid_argument);
  }

}  // TEST_SUITE
