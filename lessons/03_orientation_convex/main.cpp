// Lesson 03: orientation and convex tests.
//
// Draws a pentagram under the parity and nonzero rules; maps the sign of the
// orientation predicate on Kettner's grid, naive and robust; measures the rate
// of wrong signs against how nearly collinear the points are, naive and
// robust, against an exact integer oracle; counts cracks and double hits of
// Möller–Trumbore and the watertight test on rays aimed at a mesh's edges;
// and times parity, winding and the convex test against the vertex count.
// main() calls one function per section of the README.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/geometry/convex.hpp"
#include "illum/geometry/orientation.hpp"
#include "illum/geometry/parity.hpp"
#include "illum/geometry/triangle.hpp"
#include "illum/geometry/winding.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own
namespace {

Polygon flat(const std::vector<Vec2>& points) {
  std::vector<Point3> p;
  for (const Vec2& q : points) p.push_back({q.x, q.y, 0.0});
  return Polygon(p);
}

// --- the pentagram under two rules ----------------------------------------------

Image pentagram_image(int size, bool nonzero) {
  std::vector<Vec2> p;
  for (int k = 0; k < 5; ++k)
    p.push_back({std::cos(pi / 2 + k * 4 * pi / 5), std::sin(pi / 2 + k * 4 * pi / 5)});
  const Polygon star = flat(p);
  Image image(size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const Vec2 q(-1.1 + 2.2 * (i + 0.5) / size, 1.1 - 2.2 * (j + 0.5) / size);
      const int w = winding_number(star, q);
      const bool in = nonzero ? w != 0 : inside_parity(star, q);
      // Shade by the winding number so that the centre (w = 2) stands out.
      image.at(i, j) =
          in ? (w == 2 ? Color(0.85, 0.3, 0.2) : Color(0.95, 0.75, 0.2)) : Color(0.12, 0.12, 0.18);
    }
  return image;
}

// --- orientation: Kettner's grid and the wrong-sign study --------------------------

__extension__ typedef __int128 Int128;

// The exact sign for coordinates on the grid k·2⁻⁵² in [0, 32): integers
// below 2⁵⁷ once scaled, products below 2¹¹⁶. Independent of both predicates.
int oracle(const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto s = [](double x) { return static_cast<Int128>(std::ldexp(x, 52)); };
  const Int128 det = (s(a.x) - s(c.x)) * (s(b.y) - s(c.y)) - (s(a.y) - s(c.y)) * (s(b.x) - s(c.x));
  return (det > 0) - (det < 0);
}

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

Color sign_color(int s) {
  return s > 0 ? Color(0.2, 0.45, 0.9) : (s < 0 ? Color(0.9, 0.35, 0.2) : Color(0.95));
}

// Kettner et al. (2008): p = (0.5 + i·2⁻⁵³, 0.5 + j·2⁻⁵³), q = (12, 12), r = (24, 24).
Image kettner_image(bool robust, int& wrong) {
  const double u = std::ldexp(1.0, -53);
  Image image(256, 256);
  wrong = 0;
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i) {
      const Vec2 p(0.5 + i * u, 0.5 + (255 - j) * u);
      const int s = robust ? orient2d_sign(p, Vec2(12, 12), Vec2(24, 24))
                           : sign_of(orient2d_naive(p, Vec2(12, 12), Vec2(24, 24)));
      // Exactly, orient2d(p, (12,12), (24,24)) = 12 (p.y − p.x): the truth is sign(p.y − p.x).
      wrong += s != sign_of(p.y - p.x) ? 1 : 0;
      image.at(i, j) = sign_color(s);
    }
  return image;
}

double snap(double x) { return std::ldexp(std::nearbyint(std::ldexp(x, 52)), -52); }

// --- ray–triangle: Möller–Trumbore, the common non-watertight test ------------------

bool moller_trumbore(const Ray& ray, const Triangle& t) {
  const Vec3 e1 = t.b - t.a, e2 = t.c - t.a;
  const Vec3 p = cross(ray.direction, e2);
  const double det = dot(e1, p);
  if (std::abs(det) < 1e-14) return false;
  const double inv = 1.0 / det;
  const Vec3 to = ray.origin - t.a;
  const double u = dot(to, p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = cross(to, e1);
  const double v = dot(ray.direction, q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  return ray.range.contains(dot(e2, q) * inv);
}

// --- §1–2. The orientation of three points, and floating point getting its sign wrong -------

// Kettner's grid, naive and robust, and the count of wrong signs on it.
void kettner_grid(OutputFolder& out) {
  int naive_wrong = 0, robust_wrong = 0;
  out.image(
      kettner_image(false, naive_wrong), "kettner_naive",
      "Sign of orient2d(p, (12,12), (24,24)) in floating point on a 256×256 grid of ulps near (0.5, 0.5)");
  out.image(kettner_image(true, robust_wrong), "kettner_robust", "The same grid with the exact predicate");
  Table kettner({"predicate", "points", "wrong_signs"});
  kettner.add_row({std::string("naive"), std::int64_t{65536}, std::int64_t{naive_wrong}});
  kettner.add_row({std::string("robust"), std::int64_t{65536}, std::int64_t{robust_wrong}});
  out.table(kettner, "kettner", "Wrong signs on Kettner's grid (truth: the line is y = x exactly)");
}

// Nanoseconds per call of `orient` over the stored triples (a, b, c).
template <class Orient>
double ns_per_orientation(const std::vector<Vec2>& triples, Orient&& orient, double min_seconds) {
  const std::uint64_t count = triples.size() / 3;
  return nanoseconds_per_call(
      [&](std::uint64_t i) {
        const auto j = 3 * (i % count);
        do_not_optimize(orient(triples[j], triples[j + 1], triples[j + 2]));
      },
      min_seconds);
}

// Wrong-sign rate against closeness δ: a, b random on the 2⁻⁵² grid of [0,1)², c = a + t(b − a) +
// δ·(unit normal), snapped to the grid; the truth from 128-bit integers.
void orientation_sign_study(OutputFolder& out, bool quick, Rng& rng) {
  const int samples = quick ? 2000 : 200000;
  Table signs({"delta", "naive_wrong_rate", "robust_wrong_rate", "ns_naive", "ns_robust"});
  std::vector<Vec2> triples(3 * static_cast<std::size_t>(samples));
  for (int k = 1; k <= 18; ++k) {
    const double delta = std::pow(10.0, -k);
    int wrong_naive = 0, wrong_robust = 0;
    for (int n = 0; n < samples; ++n) {
      const Vec2 a(snap(rng.uniform()), snap(rng.uniform())), b(snap(rng.uniform()), snap(rng.uniform()));
      const Vec2 d = b - a;
      const Vec2 normal = Vec2(-d.y, d.x) / std::max(length(d), 1e-300);
      const Vec2 c0 = a + rng.uniform() * d + (rng.uniform() < 0.5 ? -delta : delta) * normal;
      const Vec2 c(snap(std::clamp(c0.x, 0.0, 0.999)), snap(std::clamp(c0.y, 0.0, 0.999)));
      const int truth = oracle(a, b, c);
      wrong_naive += sign_of(orient2d_naive(a, b, c)) != truth;
      wrong_robust += orient2d_sign(a, b, c) != truth;
      triples[3 * n] = a, triples[3 * n + 1] = b, triples[3 * n + 2] = c;
    }
    const double seconds = quick ? 0.002 : 0.03;
    const double ns_naive = ns_per_orientation(
        triples, [](const Vec2& a, const Vec2& b, const Vec2& c) { return orient2d_naive(a, b, c); },
        seconds);
    const double ns_robust = ns_per_orientation(
        triples, [](const Vec2& a, const Vec2& b, const Vec2& c) { return orient2d_sign(a, b, c); }, seconds);
    signs.add_row(
        {delta, double(wrong_naive) / samples, double(wrong_robust) / samples, ns_naive, ns_robust});
  }
  out.table(signs, "orientation_signs",
            "Rate of wrong orientation signs and time per call against the distance δ of c from the line ab");
  const PlotCurve curve{.table = "orientation_signs.csv", .x = "delta"};
  PlotCurve naive = curve, robust = curve;
  naive.y = "naive_wrong_rate", naive.title = "naive";
  robust.y = "robust_wrong_rate", robust.title = "robust (exact)";
  out.plot({.title = "Wrong orientation signs: naive vs robust (robust is 0 everywhere)",
            .x_label = "distance δ of c from the line ab",
            .y_label = "fraction of wrong signs",
            .log_x = true,
            .log_y = true,
            .curves = {naive, robust}},
           "orientation_signs", "Fraction of wrong signs against δ (log-log; zeros are not drawn)");
}

// --- §3. Oriented crossings: the winding number -----------------------------------------------

void pentagram_pictures(OutputFolder& out, bool quick) {
  const int size = quick ? 96 : 400;
  out.image(pentagram_image(size, false), "pentagram_parity",
            "Pentagram, parity rule: the centre (winding 2) is a hole");
  out.image(pentagram_image(size, true), "pentagram_nonzero",
            "Pentagram, nonzero rule: the centre (winding 2) is filled");
}

// --- §4. Convex polygons: the cost of parity, winding and the convex test ----------------------

// Its own random stream: the queries only set the timings, and §5's rays keep theirs.
void containment_cost(OutputFolder& out, bool quick, std::uint64_t seed) {
  Rng rng(seed, 4);
  Table cost({"vertices", "ns_parity", "ns_winding", "ns_convex"});
  const int max_vertices = quick ? 128 : 4096;
  for (int n = 4; n <= max_vertices; n *= 2) {
    std::vector<Vec2> ngon;
    for (int k = 0; k < n; ++k) ngon.push_back({std::cos(2 * pi * k / n), std::sin(2 * pi * k / n)});
    const ConvexPolygon convex(flat(ngon));
    const Polygon& p = convex.polygon();
    std::vector<Vec2> queries(1024);
    for (Vec2& q : queries) q = Vec2(rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double s = quick ? 0.002 : 0.04;
    const double t_parity = nanoseconds_per_call(
        [&](std::uint64_t i) { do_not_optimize(inside_parity(p, queries[i & 1023])); }, s);
    const double t_winding = nanoseconds_per_call(
        [&](std::uint64_t i) { do_not_optimize(winding_number(p, queries[i & 1023])); }, s);
    const double t_convex = nanoseconds_per_call(
        [&](std::uint64_t i) { do_not_optimize(inside_convex(convex, queries[i & 1023])); }, s);
    cost.add_row({std::int64_t{n}, t_parity, t_winding, t_convex});
  }
  out.table(cost, "containment_cost",
            "Nanoseconds per containment query on a regular n-gon, random points in its box");
  PlotSpec plot{.title = "Containment tests: cost per query against the vertex count",
                .x_label = "vertices n",
                .y_label = "ns per query",
                .log_x = true,
                .log_y = true};
  for (const auto& [column, title] : {std::pair{"ns_parity", "parity"},
                                      {"ns_winding", "winding number"},
                                      {"ns_convex", "convex (edge signs, early exit)"}})
    plot.curves.push_back({.table = "containment_cost.csv", .x = "vertices", .y = column, .title = title});
  out.plot(plot, "containment_cost", "Cost per query of parity, winding and the convex test (log-log)");
}

// --- §5. Ray–triangle, watertight -------------------------------------------------------------

// Vertex (i, j) of a height field over the unit square meshed m × m.
Point3 height_field_vertex(int i, int j, int m) {
  const double x = double(i) / m, y = double(j) / m;
  return Point3(x, y, 0.15 * std::sin(5 * x) * std::cos(4 * y));
}

// The height field as 2·m² triangles.
std::vector<Triangle> height_field(int m) {
  const auto vertex = [m](int i, int j) { return height_field_vertex(i, j, m); };
  std::vector<Triangle> mesh;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      mesh.emplace_back(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      mesh.emplace_back(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  return mesh;
}

// Rays from above aimed at the height field's interior vertices and at points along interior edges.
std::vector<Ray> rays_at_edges(int m, int count, Rng& rng) {
  const auto vertex = [m](int i, int j) { return height_field_vertex(i, j, m); };
  std::vector<Ray> rays;
  for (int r = 0; r < count; ++r) {
    const int i = 1 + static_cast<int>(rng.below(m - 1)), j = 1 + static_cast<int>(rng.below(m - 1));
    const Point3 v = vertex(i, j);
    const Point3 ends[4] = {v, vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1)};
    const int e = static_cast<int>(rng.below(4));
    const Point3 target = e == 0 ? v : v + rng.uniform() * (ends[e] - v);
    const Point3 origin = target + Vec3(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 2.0);
    rays.push_back(Ray::toward(origin, target - origin));
  }
  return rays;
}

// Cracks (no hit) and double hits of Möller–Trumbore and the watertight test, and their cost.
void watertight_study(OutputFolder& out, bool quick, Rng& rng) {
  const int m = quick ? 8 : 24;
  const std::vector<Triangle> mesh = height_field(m);
  const int ray_count = quick ? 300 : 6000;
  const std::vector<Ray> rays = rays_at_edges(m, ray_count, rng);
  Table water({"method", "rays", "cracks_0_hits", "double_hits", "ns_per_ray_triangle_test"});
  // One call outside the parallel loop, so that an error (or an exercise's
  // NotImplemented) reaches run_program instead of terminating an OpenMP thread.
  (void)intersect(rays[0], mesh[0]);
  for (int method = 0; method < 2; ++method) {
    std::int64_t cracks = 0, doubles = 0;
#pragma omp parallel for reduction(+ : cracks, doubles) schedule(dynamic, 16)
    for (int r = 0; r < ray_count; ++r) {
      int n = 0;
      for (const Triangle& t : mesh)
        n += method == 0 ? moller_trumbore(rays[r], t) : intersect(rays[r], t).has_value();
      cracks += n == 0;
      doubles += n >= 2;
    }
    const double ns = nanoseconds_per_call(
        [&](std::uint64_t k) {
          const Ray& ray = rays[k % rays.size()];
          const Triangle& t = mesh[(k * 7919) % mesh.size()];
          do_not_optimize(method == 0 ? moller_trumbore(ray, t) : intersect(ray, t).has_value());
        },
        quick ? 0.002 : 0.05);
    water.add_row({std::string(method == 0 ? "Möller–Trumbore" : "watertight (exact, tie-broken)"),
                   std::int64_t{ray_count}, cracks, doubles, ns});
  }
  out.table(water, "watertight",
            "Rays aimed exactly at a mesh's interior edges and vertices: cracks and double hits");
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson03", "Orientation and convex tests",
      "Pentagram under parity and nonzero rules, naive vs robust orientation, watertight "
      "ray–triangle on a mesh's edges, and the cost of parity, winding and convex tests."};
  return illum::run_program(argc, argv, info, {}, [&](const illum::ProgramOptions& options) {
    using namespace illum;
    OutputFolder out(options.out, info.id, info.title);
    const bool quick = options.quick;
    Rng rng(options.seed);  // §2 and §5 draw from it in turn
    report_progress(info.id, "orientation", 0, 4);
    kettner_grid(out);  // §1–2
    orientation_sign_study(out, quick, rng);
    report_progress(info.id, "pentagram", 1, 4);
    pentagram_pictures(out, quick);  // §3
    report_progress(info.id, "cost study", 2, 4);
    containment_cost(out, quick, options.seed);  // §4
    report_progress(info.id, "watertight", 3, 4);
    watertight_study(out, quick, rng);  // §5
    report_progress(info.id, "done", 4, 4);
    out.finish();
  });
}
