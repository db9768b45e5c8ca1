// Lesson 02: the plane hit and containment by parity.
//
// Renders stars, a notched comb and a polygon with holes standing on a
// checkered ground plane through the pinhole camera; draws a tiling of the
// square under three boundary rules (half-open, closed, open) and counts the
// points each rule claims 0, 1 or 2+ times; and measures the cost of the
// parity test against the number of vertices.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/geometry/parity.hpp"
#include "illum/geometry/plane.hpp"
#include "illum/geometry/polygon.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own
namespace {

// Points of a planar outline, placed in 3D: (u, v) ↦ centre + u·right + v·up.
std::vector<Point3> place(const std::vector<Vec2>& outline, const Point3& centre, const Vec3& right,
                          const Vec3& up) {
  std::vector<Point3> p;
  p.reserve(outline.size());
  for (const Vec2& q : outline) p.push_back(centre + q.x * right + q.y * up);
  return p;
}

// A star with `points` tips: 2·points vertices alternating between two radii.
std::vector<Vec2> star(int points, double outer, double inner, double phase = pi / 2) {
  std::vector<Vec2> s;
  for (int k = 0; k < 2 * points; ++k) {
    const double a = phase + k * pi / points;
    const double r = k % 2 == 0 ? outer : inner;
    s.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return s;
}

// A comb: a bar with `teeth` teeth separated by rectangular notches.
std::vector<Vec2> comb(int teeth, double width, double height) {
  const double step = width / (2 * teeth - 1);
  std::vector<Vec2> c{{-width / 2, -height / 2}, {width / 2, -height / 2}};
  for (int t = teeth - 1; t >= 0; --t) {
    const double x1 = -width / 2 + (2 * t + 1) * step, x0 = x1 - step;
    c.push_back({x1, height / 2});
    c.push_back({x0, height / 2});
    if (t > 0) {
      c.push_back({x0, 0.0});
      c.push_back({x0 - step, 0.0});
    }
  }
  return c;
}

std::vector<Vec2> regular(int n, double r, Vec2 centre, bool clockwise) {
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) {
    const double a = (clockwise ? -1.0 : 1.0) * 2 * pi * k / n;
    p.push_back(centre + r * Vec2(std::cos(a), std::sin(a)));
  }
  return p;
}

struct Shape {
  Polygon polygon;
  Color color;
};

Image render_scene(int width, int height) {
  const Vec3 up(0, 1, 0);
  const Vec3 tilt_right = normalize(Vec3(1, 0, -0.35)), tilt_left = normalize(Vec3(1, 0, 0.35));
  std::vector<Shape> shapes;
  shapes.push_back(
      {Polygon(place(star(5, 1.3, 0.5), Point3(-3.1, 0.4, 0), tilt_left, up)), Color(0.9, 0.6, 0.1)});
  shapes.push_back(
      {Polygon(place(comb(4, 2.4, 1.6), Point3(0, 0.1, -0.5), Vec3(1, 0, 0), up)), Color(0.2, 0.6, 0.9)});
  // A frame with three holes: a square, a triangle and a 24-gon, wound either way.
  std::vector<std::vector<Point3>> holes{
      place({{-0.8, 0.2}, {-0.8, 0.8}, {-0.2, 0.8}, {-0.2, 0.2}}, Point3(3.1, 0.2, 0), tilt_right, up),
      place({{0.2, 0.2}, {0.8, 0.2}, {0.5, 0.8}}, Point3(3.1, 0.2, 0), tilt_right, up),
      place(regular(24, 0.45, {0.0, -0.5}, true), Point3(3.1, 0.2, 0), tilt_right, up)};
  shapes.push_back({Polygon(place({{-1.1, -1.1}, {1.1, -1.1}, {1.1, 1.1}, {-1.1, 1.1}}, Point3(3.1, 0.2, 0),
                                  tilt_right, up),
                            holes),
                    Color(0.8, 0.25, 0.3)});
  // A small star lying flat on the ground: its normal is mostly y, so y is dropped.
  shapes.push_back({Polygon(place(star(7, 0.9, 0.45), Point3(0, -1.49, 2.2), Vec3(1, 0, 0), Vec3(0, 0, 1))),
                    Color(0.95, 0.9, 0.3)});
  const Plane ground(Vec3(0, 1, 0), 1.5);  // y = −1.5
  const Vec3 light = normalize(Vec3(-0.4, 0.8, 0.6));

  const PinholeCamera camera(Point3(0, 1.2, 8.5), Point3(0, -0.2, 0), up, 45.0, width, height);
  Image image(width, height);
  // One call outside the parallel loop, so that an error (or an exercise's
  // NotImplemented) reaches run_program instead of terminating an OpenMP thread.
  (void)intersect(camera.pixel_ray(0, 0), shapes[0].polygon);
#pragma omp parallel for schedule(dynamic, 4)
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const Ray ray = camera.pixel_ray(i, j);
      double nearest = infinity;
      Color color = Color(0.55, 0.65, 0.8) * (0.6 + 0.4 * ray.direction.y);  // sky
      for (const Shape& shape : shapes) {
        const auto hit = intersect(ray, shape.polygon);
        if (hit && hit->s < nearest) {
          nearest = hit->s;
          color = shape.color * (0.25 + 0.75 * std::abs(dot(hit->normal, light)));
        }
      }
      if (const auto s = intersect(ray, ground); s && *s < nearest) {
        const Point3 p = ray.at(*s);
        const bool dark = (static_cast<int>(std::floor(p.x)) + static_cast<int>(std::floor(p.z))) % 2 != 0;
        color = (dark ? Color(0.3) : Color(0.7)) * (0.25 + 0.75 * light.y);
      }
      image.at(i, j) = color;
    }
  return image;
}

// --- the tiling and three boundary rules ---------------------------------------

std::vector<Polygon> tiling() {
  const auto flat = [](std::vector<Vec2> p) {
    std::vector<Point3> q;
    for (const Vec2& v : p) q.push_back({v.x, v.y, 0});
    return q;
  };
  std::vector<Polygon> t;
  t.emplace_back(flat({{0, 0}, {2, 0}, {2, 2}, {0, 2}}),
                 std::vector<std::vector<Point3>>{flat({{0.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}, {1.5, 0.5}})});
  t.emplace_back(flat({{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}}));
  t.emplace_back(flat({{2, 0}, {3, 0}, {3, 1}, {4, 1}, {4, 2}, {2, 2}}));
  t.emplace_back(flat({{3, 0}, {4, 0}, {4, 1}}));
  t.emplace_back(flat({{3, 0}, {4, 1}, {3, 1}}));
  t.emplace_back(flat({{0, 2}, {2, 2}, {0, 4}}));
  t.emplace_back(flat({{2, 2}, {2, 4}, {0, 4}}));
  const Vec2 corners[4] = {{2, 2}, {4, 2}, {4, 4}, {2, 4}};
  for (int i = 0; i < 4; ++i) t.emplace_back(flat({corners[i], corners[(i + 1) % 4], {3, 3}}));
  return t;
}

// q on the closed segment ab (exact for the tiling's binary-grid coordinates).
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& q) {
  const double det = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
  return det == 0.0 && q.x >= std::min(a.x, b.x) && q.x <= std::max(a.x, b.x) && q.y >= std::min(a.y, b.y) &&
         q.y <= std::max(a.y, b.y);
}

bool on_boundary(const Polygon& p, const Vec2& q) {
  for (std::size_t l = 0; l < p.loop_count(); ++l) {
    const auto loop = p.loop_2d(l);
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
      if (on_segment(loop[j], loop[i], q)) return true;
  }
  return false;
}

enum class Rule { half_open, closed, open };

bool claims(const Polygon& p, const Vec2& q, Rule rule) {
  switch (rule) {
    case Rule::closed:
      return on_boundary(p, q) || inside_parity(p, q);
    case Rule::open:
      return !on_boundary(p, q) && inside_parity(p, q);
    default:
      return inside_parity(p, q);
  }
}

// Colours each point of a grid by the piece that claims it; white where two
// or more do, black where none does inside the square.
Image tiling_image(const std::vector<Polygon>& pieces, Rule rule, int size, int counts[3]) {
  Image image(size, size);
  counts[0] = counts[1] = counts[2] = 0;
  const double step = 4.0 / (size - 1);  // pixel centres fall on every edge of the tiling
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const Vec2 q(i * step, 4.0 - j * step);
      int n = 0, owner = -1;
      for (std::size_t k = 0; k < pieces.size(); ++k)
        if (claims(pieces[k], q, rule)) ++n, owner = static_cast<int>(k);
      const bool interior_of_square = q.x < 4.0 && q.y < 4.0;
      if (interior_of_square) ++counts[std::min(n, 2)];
      Color c(0.0);
      if (n >= 2)
        c = Color(1.0);
      else if (n == 1)
        c = 0.35 + 0.55 * colormap_viridis(owner / double(pieces.size() - 1));
      else if (!interior_of_square)
        c = Color(0.15);
      image.at(i, j) = c;
    }
  return image;
}

// --- §4. Crossing parity and the half-open rule: a tiling under three rules -----------------

void tiling_study(OutputFolder& out, bool quick) {
  const std::vector<Polygon> pieces = tiling();
  const int size = quick ? 129 : 513;  // 4/(size − 1) is a power of two: every edge is sampled exactly
  Table rules({"rule", "points", "claimed_0", "claimed_1", "claimed_2_or_more"});
  const std::pair<Rule, std::string> all_rules[3] = {
      {Rule::half_open, "half-open"}, {Rule::closed, "closed"}, {Rule::open, "open"}};
  for (const auto& [rule, name] : all_rules) {
    int counts[3];
    const Image img = tiling_image(pieces, rule, size, counts);
    out.image(img, "tiling_" + name,
              "The tiling under the " + name + " rule: white = claimed twice or more, black = by none");
    rules.add_row({name, std::int64_t{counts[0] + counts[1] + counts[2]}, std::int64_t{counts[0]},
                   std::int64_t{counts[1]}, std::int64_t{counts[2]}});
  }
  out.table(rules, "tiling_rules",
            "Grid points of [0,4)² claimed 0, 1 or 2+ times by the 11 pieces of the tiling");
}

// --- §5–6. Holes and the ray–polygon hit: the rendered scene ------------------------------------

void render_polygons(OutputFolder& out, bool quick) {
  out.image(quick ? render_scene(240, 135) : render_scene(960, 540), "polygons",
            "Stars, a notched comb and a frame with three holes, hit by ray–plane (erratum 2) plus parity");
}

// --- §7. What it costs: parity and the whole ray–polygon test against the vertex count -----------

void parity_cost(OutputFolder& out, bool quick, std::uint64_t seed) {
  Table cost({"vertices", "ns per parity query", "ns per vertex", "ns per ray-polygon test"});
  Rng rng(seed);
  const int max_vertices = quick ? 256 : 8192;
  const double min_seconds = quick ? 0.002 : 0.05;
  for (int n = 8; n <= max_vertices; n *= 2) {
    const Polygon p(place(star(n / 2, 1.0, 0.5), Point3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)));
    std::vector<Vec2> queries(1024);
    std::vector<Ray> rays;
    for (Vec2& q : queries) q = Vec2(rng.uniform(-1, 1), rng.uniform(-1, 1));
    for (const Vec2& q : queries)
      rays.push_back(Ray::toward(Point3(0.1, -0.2, 3), Point3(q, 0) - Point3(0.1, -0.2, 3)));
    // One thread, best of three runs.
    const double ns = best_nanoseconds_per_call(
        3, [&](std::uint64_t i) { do_not_optimize(inside_parity(p, queries[i & 1023])); }, min_seconds);
    const double ns_ray = best_nanoseconds_per_call(
        3, [&](std::uint64_t i) { do_not_optimize(intersect(rays[i & 1023], p).has_value()); }, min_seconds);
    cost.add_row({std::int64_t{n}, ns, ns / n, ns_ray});
  }
  out.table(cost, "parity_cost",
            "Cost of the parity test and of the full ray–polygon test against the vertex count");
  out.plot({.title = "Parity test: cost grows linearly with the vertex count",
            .x_label = "vertices n",
            .y_label = "ns per query",
            .log_x = true,
            .log_y = true,
            .curves = {{.table = "parity_cost.csv",
                        .x = "vertices",
                        .y = "ns per parity query",
                        .title = "inside\\_parity (2D)"},
                       {.table = "parity_cost.csv",
                        .x = "vertices",
                        .y = "ns per ray-polygon test",
                        .title = "ray–polygon (plane + box + parity)"}}},
           "parity_cost", "Nanoseconds per query against the number of vertices (log-log)");
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson02", "The plane hit and containment by parity",
      "Renders polygons (stars, a comb, a polygon with holes) through the pinhole camera, "
      "checks a tiling under three boundary rules, and measures the parity test's cost "
      "against the vertex count."};
  return illum::run_program(argc, argv, info, {}, [&](const illum::ProgramOptions& options) {
    using namespace illum;
    OutputFolder out(options.out, info.id, info.title);
    report_progress(info.id, "tiling", 0, 3);
    tiling_study(out, options.quick);  // §4
    report_progress(info.id, "render", 1, 3);
    render_polygons(out, options.quick);  // §5–6
    report_progress(info.id, "cost study", 2, 3);
    parity_cost(out, options.quick, options.seed);  // §7
    report_progress(info.id, "done", 3, 3);
    out.finish();
  });
}
