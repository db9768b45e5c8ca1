// Lesson 04 reference program: CSG by combining ray intervals.
//
// Renders three classic CSG solids (a die, a lens, a drilled cube) through
// the pinhole camera, shaded and as normal images, and runs the two studies:
//  (a) coincident faces: artefact pixels against the sliver tolerance, and
//      the thin features that too large a tolerance erases;
//  (b) cost against tree depth, with and without bounding-box pruning.

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/geometry/csg_tree.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"

namespace illum {
namespace {

// ---- scenes --------------------------------------------------------------------

// Surface tags: which colour a surface gets in the shaded images.
enum Tag { body = 0, pip = 1, second = 1, drill_x = 1, drill_y = 2, drill_z = 3 };

// A die: the rounded cube [−1,1]³ ∩ ball(1.38), minus 21 small balls for the
// pips (opposite faces add up to seven).
CsgNodePtr make_die() {
  const CsgNodePtr rounded = csg_intersection(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                                              csg_solid(SolidSphere(Point3(0), 1.38), body));
  struct Face {
    Vec3 normal, u, v;
    int count;
  };
  const std::array<Face, 6> faces{{{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 1},
                                   {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}, 6},
                                   {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 2},
                                   {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 5},
                                   {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, 3},
                                   {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}, 4}}};
  std::vector<CsgNodePtr> pips;
  for (const Face& face : faces) {
    // Pip positions on the face, in units of the face's half width.
    std::vector<Vec2> at;
    const int n = face.count;
    if (n % 2 == 1) at.push_back(Vec2(0, 0));
    if (n >= 2) at.push_back(Vec2(-0.5, -0.5)), at.push_back(Vec2(0.5, 0.5));
    if (n >= 4) at.push_back(Vec2(-0.5, 0.5)), at.push_back(Vec2(0.5, -0.5));
    if (n == 6) at.push_back(Vec2(-0.5, 0)), at.push_back(Vec2(0.5, 0));
    for (const Vec2& p : at) {
      pips.push_back(csg_solid(SolidSphere(1.06 * face.normal + p.x * face.u + p.y * face.v, 0.2), pip));
    }
  }
  return csg_difference(rounded, csg_union_all(pips));
}

// A lens: the common part of two unit balls whose centres are 1.2 apart.
CsgNodePtr make_lens() {
  return csg_intersection(csg_solid(SolidSphere(Point3(0, 0, 0.6), 1.0), body),
                          csg_solid(SolidSphere(Point3(0, 0, -0.6), 1.0), second));
}

// A drilled cube: [−1,1]³ minus three cylinders along x, y and z that
// overshoot the faces (the modeller's habit that avoids coincident faces).
CsgNodePtr make_drilled_cube() {
  const auto drill = [](const Vec3& axis, int tag) {
    return csg_solid(SolidCylinder(-1.5 * axis, axis, 0.45, 3.0), tag);
  };
  return csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                        csg_union(drill(Vec3(1, 0, 0), drill_x),
                                  csg_union(drill(Vec3(0, 1, 0), drill_y), drill(Vec3(0, 0, 1), drill_z))));
}

// A blind hole whose opening lies exactly in the box's top face z = 1: the
// cylinder's top cap and the box face are the same plane, computed two ways.
CsgNodePtr make_blind_hole() {
  return csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                        csg_solid(SolidCylinder(Point3(0, 0, 0), Vec3(0, 0, 1), 0.5, 1.0), drill_y));
}

// A square pocket sharing the top face: both faces from the same slab arithmetic.
CsgNodePtr make_pocket() {
  return csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                        csg_solid(SolidBox(Point3(-0.5, -0.5, 0), Point3(0.5, 0.5, 1)), drill_y));
}

// A coin of thickness w: a slab ∩ a ball, a genuinely thin solid.
constexpr double coin_thickness = 1e-4;
CsgNodePtr make_coin() {
  return csg_intersection(
      csg_solid(SolidSlab(Vec3(0, 0, 1), -0.5 * coin_thickness, 0.5 * coin_thickness), body),
      csg_solid(SolidSphere(Point3(0), 1.0), body));
}

// ---- rendering -----------------------------------------------------------------

Color background(const Ray& ray) { return Color(0.05, 0.06, 0.08) + 0.12 * (0.5 + 0.5 * ray.direction.z); }

// Lambert shading under one directional light plus a little ambient light,
// coloured by the tag of the surface that made the hit.
Color shade(const Ray& ray, const CsgHit& hit) {
  static const std::array<Color, 4> palette{Color(0.85, 0.82, 0.74), Color(0.55, 0.08, 0.06),
                                            Color(0.15, 0.45, 0.75), Color(0.2, 0.6, 0.25)};
  const Vec3 light = normalize(Vec3(0.4, -0.7, 1.0));
  Vec3 n = hit.normal;
  if (dot(n, ray.direction) > 0.0) n = -n;  // seen from inside: light the side facing the eye
  const Color base = palette[static_cast<std::size_t>(hit.surface) % palette.size()];
  return base * (0.15 + 0.85 * std::max(0.0, dot(n, light)));
}

Color normal_colour(const Ray&, const CsgHit& hit) { return 0.5 * (hit.normal + Vec3(1.0)); }

using Shader = std::function<Color(const Ray&, const CsgHit&)>;

Image render(const CsgTree& tree, const PinholeCamera& camera, const CsgOptions& options,
             const Shader& shader, CsgCounters& total) {
  Image image(camera.width(), camera.height());
#pragma omp parallel
  {
    CsgCounters counters;  // one per thread, added up at the end
#pragma omp for schedule(dynamic, 4)
    for (int y = 0; y < camera.height(); ++y) {
      for (int x = 0; x < camera.width(); ++x) {
        const Ray ray = camera.pixel_ray(x, y);
        ++counters.work.primary_rays;
        const auto hit = intersect(ray, tree, options, counters);
        image.at(x, y) = hit ? shader(ray, *hit) : background(ray);
      }
    }
#pragma omp critical
    total += counters;
  }
  return image;
}

// ---- study (a): coincident faces against the sliver tolerance ---------------

// A hit on the removed face: on the plane z = 1, strictly inside the opening.
bool on_removed_face(const CsgHit& hit, bool round_hole) {
  const Point3& p = hit.point;
  if (std::abs(p.z - 1.0) > 1e-9) return false;
  return round_hole ? std::hypot(p.x, p.y) < 0.5 - 1e-9 : std::max(std::abs(p.x), std::abs(p.y)) < 0.5 - 1e-9;
}

// Pixels whose ray hits the removed face (the artefact), and the image that shows them in red.
int count_face_artefacts(const CsgTree& tree, const PinholeCamera& camera, double tolerance, bool round_hole,
                         Image* picture) {
  CsgOptions options;
  options.sliver_tolerance = tolerance;
  int artefacts = 0;
#pragma omp parallel for reduction(+ : artefacts) schedule(dynamic, 4)
  for (int y = 0; y < camera.height(); ++y) {
    CsgCounters counters;
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      const auto hit = intersect(ray, tree, options, counters);
      const bool bad = hit && on_removed_face(*hit, round_hole);
      artefacts += bad ? 1 : 0;
      if (picture) picture->at(x, y) = bad ? Color(1.0, 0.1, 0.0) : hit ? shade(ray, *hit) : background(ray);
    }
  }
  return artefacts;
}

// Pixels where the thin coin should be seen (the ray meets the plane z = 0
// well inside the rim: closed form) but the CSG evaluation reports a miss.
int count_missing_coin(const CsgTree& coin, const PinholeCamera& camera, double tolerance, int& expected) {
  CsgOptions options;
  options.sliver_tolerance = tolerance;
  int missing = 0, should_hit = 0;
#pragma omp parallel for reduction(+ : missing, should_hit) schedule(dynamic, 4)
  for (int y = 0; y < camera.height(); ++y) {
    CsgCounters counters;
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      if (ray.direction.z == 0.0) continue;
      const double s = -ray.origin.z / ray.direction.z;  // plane z = 0
      const Point3 p = ray.at(s);
      if (s <= 0.0 || std::hypot(p.x, p.y) > 0.98) continue;
      ++should_hit;
      if (!intersect(ray, coin, options, counters)) ++missing;
    }
  }
  expected = should_hit;
  return missing;
}

void coincident_face_study(OutputFolder& out, int width, int height) {
  const PinholeCamera camera(Point3(0.9, -2.1, 3.3), Point3(0, 0, 0.4), Vec3(0, 0, 1), 32.0, width, height);
  const CsgTree blind(make_blind_hole()), pocket(make_pocket()), coin(make_coin());
  const PinholeCamera coin_camera(Point3(0, -2.6, 2.6), Point3(0), Vec3(0, 0, 1), 40.0, width, height);

  // Pixels whose ray enters the opening (meets the plane z = 1 inside the rim): closed form.
  int opening_pixels = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      const Point3 p = ray.at((1.0 - ray.origin.z) / ray.direction.z);
      if (std::hypot(p.x, p.y) < 0.5) ++opening_pixels;
    }
  }

  Table table({"tolerance", "blind_hole_artefacts", "pocket_artefacts", "coin_missing", "opening_pixels",
               "coin_pixels", "artefact_percent", "coin_lost_percent"});
  const std::vector<double> tolerances{0.0,   1e-16, 1e-15, 3e-15, 1e-14, 1e-13, 1e-12,
                                       1e-10, 1e-8,  1e-6,  1e-5,  1e-4,  2e-4,  1e-3};
  int step = 0;
  for (const double tolerance : tolerances) {
    int coin_pixels = 0;
    const int blind_bad = count_face_artefacts(blind, camera, tolerance, true, nullptr);
    const int pocket_bad = count_face_artefacts(pocket, camera, tolerance, false, nullptr);
    const int coin_missing = count_missing_coin(coin, coin_camera, tolerance, coin_pixels);
    table.add_row({tolerance, std::int64_t{blind_bad}, std::int64_t{pocket_bad}, std::int64_t{coin_missing},
                   std::int64_t{opening_pixels}, std::int64_t{coin_pixels},
                   100.0 * blind_bad / opening_pixels, 100.0 * coin_missing / coin_pixels});
    report_progress("lesson04", "coincident-face study", ++step, static_cast<int>(tolerances.size()));
  }
  out.table(table, "coincident_faces",
            "Artefact pixels (the removed top face showing inside the blind hole or the square pocket) and "
            "pixels of a 1e-4 thick coin that vanish, against the sliver tolerance.");

  PlotSpec plot{.title = "Coincident faces: artefacts vs the sliver tolerance",
                .x_label = "sliver tolerance (units of s; tolerance 0 is not drawn)",
                .y_label = "% of the pixels concerned",
                .log_x = true};
  for (const auto& [column, title] : {std::pair{"artefact_percent", "blind hole: removed face showing"},
                                      {"coin_lost_percent", "thin coin (1e-4 thick): pixels lost"}})
    plot.curves.push_back(
        {.table = "coincident_faces.csv", .x = "tolerance", .y = column, .x_positive = true, .title = title});
  out.plot(plot, "coincident_faces",
           "Too small a tolerance shows the removed face; too large erases thin solids.");

  Image raw(width, height), clean(width, height);
  count_face_artefacts(blind, camera, 0.0, true, &raw);
  count_face_artefacts(blind, camera, CsgOptions{}.sliver_tolerance, true, &clean);
  out.image(raw, "blind_hole_tolerance_0",
            "A blind hole whose opening lies in the box's top face, sliver tolerance 0: red pixels are the "
            "removed face, left as slivers one ulp long.");
  out.image(clean, "blind_hole_tolerance_default",
            "The same with the default sliver tolerance 1e-9: no artefact.");
}

// ---- study (b): cost against tree depth, with and without pruning -------------

void depth_study(OutputFolder& out, int width, int height, bool quick) {
  Table table({"depth", "primitives", "pruning", "tests_per_ray", "box_tests_per_ray", "ns_per_ray",
               "hits_differing"});
  const int max_level = 6;
  std::array<std::vector<std::vector<Table::Cell>>, 2> grouped;  // [0] without pruning, [1] with
  for (int level = 1; level <= max_level; ++level) {
    // 2^level balls on a grid, united as a balanced tree (rows first, then columns).
    const int n = 1 << level, columns = 1 << ((level + 1) / 2), rows = n / columns;
    std::vector<CsgNodePtr> balls;
    for (int i = 0; i < n; ++i) {
      const Point3 centre(i % columns - 0.5 * (columns - 1), i / columns - 0.5 * (rows - 1), 0.0);
      balls.push_back(csg_solid(SolidSphere(centre, 0.35), i % 4));
    }
    const CsgTree tree(csg_union_all(balls));
    const double span = std::max(columns, rows);
    const PinholeCamera camera(Point3(0, -0.6 * span, 1.8 * span), Point3(0), Vec3(0, 0, 1), 40.0, width,
                               height);
    std::vector<Ray> rays;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) rays.push_back(camera.pixel_ray(x, y));

    std::vector<double> reference_s;
    for (const bool prune : {false, true}) {
      CsgOptions options;
      options.prune_with_bounds = prune;
      CsgCounters counters;
      std::vector<double> hit_s(rays.size(), -1.0);
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const auto hit = intersect(rays[i], tree, options, counters);
        hit_s[i] = hit ? hit->s : -1.0;
      }
      if (!prune) reference_s = hit_s;
      std::int64_t differing = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) differing += hit_s[i] != reference_s[i] ? 1 : 0;
      // Time on one thread: the cost of one ray, not the machine's width. The
      // best of three runs, since other work on the machine only ever adds time.
      CsgCounters scratch;
      const double ns = best_nanoseconds_per_call(
          3,
          [&](std::uint64_t i) { do_not_optimize(intersect(rays[i % rays.size()], tree, options, scratch)); },
          quick ? 0.002 : 0.05);
      const double per_ray = 1.0 / static_cast<double>(rays.size());
      grouped[prune ? 1 : 0].push_back({std::int64_t{tree.depth()}, std::int64_t{n},
                                        std::string(prune ? "on" : "off"),
                                        per_ray * static_cast<double>(counters.work.intersection_tests),
                                        per_ray * static_cast<double>(counters.box_tests), ns, differing});
    }
    report_progress("lesson04", "depth study", level, max_level);
  }
  // All "off" rows first, then all "on" rows, so each plotted series is one unbroken line.
  for (auto& group : grouped)
    for (auto& row : group) table.add_row(std::move(row));
  out.table(table, "depth_cost",
            "Cost per camera ray of a balanced union of 2^k balls: primitive tests, box tests and time, with "
            "and without bounding-box pruning; hits_differing counts rays whose hit changed (must be 0).");
  for (const auto& [y, label, name, caption] :
       {std::tuple{"ns_per_ray", "ns per ray (one thread)", "depth_cost_time",
                   "Time per ray grows linearly without pruning, far slower with it."},
        std::tuple{"tests_per_ray", "primitive tests per ray", "depth_cost_tests",
                   "Primitive tests per ray, counted with CsgCounters."}}) {
    PlotSpec plot{.title = "CSG cost per ray against the number of primitives",
                  .x_label = "primitives in the tree",
                  .y_label = label,
                  .log_x = true,
                  .log_y = true};
    for (const auto& [pruning, title] : {std::pair{"off", "no pruning"}, {"on", "bounding-box pruning"}})
      plot.curves.push_back({.table = "depth_cost.csv",
                             .x = "primitives",
                             .y = y,
                             .where = {{"pruning", pruning}},
                             .title = title});
    out.plot(plot, name, caption);
  }
}

// ---- the gallery ----------------------------------------------------------------

void render_gallery(OutputFolder& out, int width, int height) {
  struct Solid {
    std::string name, caption;
    CsgNodePtr root;
    Point3 eye;
  };
  const std::vector<Solid> solids{
      {"die", "A die: (cube ∩ ball) − 21 balls for the pips; the pips' surfaces come from subtracted balls.",
       make_die(), Point3(3.4, -4.4, 3.6)},
      {"lens", "A lens: the intersection of two balls; each face is coloured by the ball that made it.",
       make_lens(), Point3(1.7, -2.1, 1.2)},
      {"drilled_cube",
       "A drilled cube: cube − three cylinders; each hole's wall takes its cylinder's colour.",
       make_drilled_cube(), Point3(3.4, -2.8, 2.6)}};
  CsgCounters counters;
  for (const Solid& solid : solids) {
    const CsgTree tree(solid.root);
    const PinholeCamera camera(solid.eye, Point3(0), Vec3(0, 0, 1), 30.0, width, height);
    out.image(render(tree, camera, CsgOptions{}, shade, counters), solid.name, solid.caption);
    out.image(
        render(tree, camera, CsgOptions{}, normal_colour, counters), solid.name + "_normals",
        "Outward normals of the " + solid.name + " as colours (n + 1)/2; subtracted surfaces are reversed.");
  }
  out.text("gallery_counters.txt", counters.work.summary() + "\n",
           "Work counted while rendering the gallery.");
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson04", "CSG by combining ray intervals",
      "Renders a die, a lens and a drilled cube built by CSG, then measures coincident-face "
      "artefacts against the sliver tolerance and cost against tree depth with and without "
      "bounding-box pruning."};
  return illum::run_program(argc, argv, info, {}, [&](const illum::ProgramOptions& options) {
    using namespace illum;
    OutputFolder out(options.out, info.id, info.title);
    const int width = options.quick ? 120 : 480, height = options.quick ? 90 : 360;
    render_gallery(out, width, height);
    coincident_face_study(out, options.quick ? 120 : 400, options.quick ? 90 : 300);
    depth_study(out, options.quick ? 32 : 128, options.quick ? 24 : 96, options.quick);
    out.finish();
  });
}
