// Lesson 10: the hemicube. Draws the delta form factors and the five
// item-buffer faces of one placement in a room, and measures the hemicube's
// errors: against exact factors vs resolution, the aliasing of small patches
// and what a random rotation does to it, the point-sampling error for nearby
// patches, and the price: error (fixed and randomly rotated) against
// resolution and the time of one placement. Finally times full matrices of a
// ~2,000-patch room. main() calls one function per section of the README.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <omp.h>

#include "illum/core/error.hpp"
#include "illum/core/image.hpp"
#include "illum/core/log_log_fit.hpp"
#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own
namespace {

// --- exact references: the library's closed forms and contour formula ----------------------

// Howell B-3: differential area to a parallel rectangle a × b with a corner above it at height c
// (the hemicube's top-face corner formula, eq. 10.4, scaled to height c).
double parallel_corner(double a, double b, double c) { return top_face_corner(a / c, b / c); }

// Howell B-4: differential area to a perpendicular rectangle of height a, width b at distance c
// (the side-face corner formula, eq. 10.5, scaled to distance c).
double perpendicular_corner(double a, double b, double c) { return side_face_corner(b / c, a / c); }

// The exact factor from the receiver at the origin (normal +z) to the front of `target`:
// the contour formula of lesson 09.
double exact_from_origin(const Patch& target) {
  return point_polygon_form_factor(Point3(0), Vec3(0, 0, 1), target);
}

// `polygon` as a patch whose front faces the origin.
Patch facing_origin(const std::vector<Point3>& polygon) {
  Patch target = make_patch(polygon);
  if (dot(target.normal, target.centroid) > 0)
    target = make_patch(std::vector<Point3>(polygon.rbegin(), polygon.rend()));
  return target;
}

// --- scenes ------------------------------------------------------------------------------

// The six faces of the box [lo, hi], meshed m × m, normals inwards (a room) or outwards (a block).
void add_box(std::vector<Patch>& patches, const Point3& lo, const Point3& hi, int m, bool inward,
             int first_surface) {
  const double q[6][4][3] = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}},
      {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}},
      {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}};
  for (int f = 0; f < 6; ++f) {
    Point3 c[4];
    for (int k = 0; k < 4; ++k) c[k] = lo + (hi - lo) * Vec3(q[f][k][0], q[f][k][1], q[f][k][2]);
    auto face = inward ? mesh_quad(c[0], c[1], c[2], c[3], m, m, Color(0.5), Color(0.0), first_surface + f)
                       : mesh_quad(c[0], c[3], c[2], c[1], m, m, Color(0.5), Color(0.0), first_surface + f);
    patches.insert(patches.end(), face.begin(), face.end());
  }
}

// A closed unit room meshed m × m per wall with a floating block meshed k × k per face:
// every direction from every patch hits a front face, so every row sums to one.
std::vector<Patch> room_with_block(int m, int k) {
  std::vector<Patch> patches;
  add_box(patches, Point3(0), Point3(1), m, true, 0);
  add_box(patches, Point3(0.3, 0.35, 0.25), Point3(0.65, 0.7, 0.6), k, false, 6);
  return patches;
}

// A small square of side s centred at c facing the origin.
std::vector<Point3> facing_square(const Point3& c, double s) {
  const Vec3 n = normalize(-c);
  const Vec3 u = normalize(cross(std::abs(n.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0), n));
  const Vec3 v = cross(n, u);
  const double h = 0.5 * s;
  return {c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v};
}

Patch receiver_at_origin(double half = 0.01) {
  return make_patch({{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}});
}

// --- the resolution study: error against exact factors vs resolution and time ---------------

// p turned by `angle` about the z axis. A factor from the origin with normal z does not change.
Point3 rotate_z(const Point3& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x - s * p.y, s * p.x + c * p.y, p.z};
}

// One configuration: the hemicube is placed on patches[receiver]; exact[j] is the exact factor
// from its centroid to patch j (0 for the receiver and for patches it cannot see).
struct StudyCase {
  std::string name;  // no commas: gnuplot splits the CSV's rows on them
  std::vector<Patch> patches;
  std::size_t receiver = 0;
  std::vector<double> exact;
};

// A point receiver at the origin (normal z) and one convex polygon, turned to face it.
// `exact` comes from Howell's catalogue and is checked against the contour formula.
StudyCase point_case(const std::string& name, const std::vector<Point3>& polygon, double exact) {
  const Patch target = facing_origin(polygon);
  const double contour = exact_from_origin(target);
  require(std::abs(exact - contour) <= 1e-12 * exact, "closed form and contour integral disagree");
  return {name, {receiver_at_origin(), target}, 0, {0.0, exact}};
}

// A whole row: a floor patch of an empty unit room meshed m × m per wall. Nothing occludes in a
// convex room, so the exact row is the contour formula from the receiver's centroid to every patch.
StudyCase room_row_case(int m) {
  StudyCase room{"room row " + std::to_string(m) + "x" + std::to_string(m) + " per wall", {}, 0, {}};
  add_box(room.patches, Point3(0), Point3(1), m, true, 0);
  const Point3 spot(0.3, 0.4, 0);
  for (std::size_t j = 0; j < room.patches.size(); ++j)
    if (room.patches[j].surface == 0 &&
        length(room.patches[j].centroid - spot) < length(room.patches[room.receiver].centroid - spot))
      room.receiver = j;
  const Patch& r = room.patches[room.receiver];
  double total = 0;
  for (std::size_t j = 0; j < room.patches.size(); ++j) {
    const auto& v = room.patches[j].vertices;
    const bool above = std::any_of(v.begin(), v.end(),
                                   [&](const Point3& p) { return dot(p - r.centroid, r.normal) > 1e-12; });
    room.exact.push_back(
        j != room.receiver && above ? point_polygon_form_factor(r.centroid, r.normal, room.patches[j]) : 0.0);
    total += room.exact.back();
  }
  require(std::abs(total - 1) < 1e-12, "the exact row of a closed room must sum to one");
  return room;
}

// Errors of one row against the exact factors, over the patches the receiver sees.
struct RowError {
  double max_abs = 0, mean_abs = 0, max_rel = 0, mean_rel = 0;
};

RowError row_error(const std::vector<double>& row, const std::vector<double>& exact) {
  RowError e;
  int seen = 0;
  for (std::size_t j = 0; j < row.size(); ++j) {
    if (exact[j] <= 0) continue;
    const double abs_error = std::abs(row[j] - exact[j]), rel_error = abs_error / exact[j];
    e.max_abs = std::max(e.max_abs, abs_error);
    e.max_rel = std::max(e.max_rel, rel_error);
    e.mean_abs += abs_error;
    e.mean_rel += rel_error;
    ++seen;
  }
  e.mean_abs /= seen;
  e.mean_rel /= seen;
  return e;
}

// --- pictures ----------------------------------------------------------------------------

// The hemicube unfolded as a cross: image coordinates (u, v) ∈ [−2, 2]², the top face in
// the middle, each side face folded out with its base (z = 0) at the outer edge.
template <class Shade>
Image unfolded(int pixels, Shade&& shade) {
  Image img(pixels, pixels, Color(1.0));
  for (int py = 0; py < pixels; ++py)
    for (int px = 0; px < pixels; ++px) {
      const double u = -2 + 4 * (px + 0.5) / pixels, v = 2 - 4 * (py + 0.5) / pixels;
      Vec3 d;
      if (std::abs(u) <= 1 && std::abs(v) <= 1)
        d = Vec3(u, v, 1);
      else if (u > 1 && std::abs(v) <= 1)
        d = Vec3(1, v, 2 - u);
      else if (u < -1 && std::abs(v) <= 1)
        d = Vec3(-1, v, 2 + u);
      else if (v > 1 && std::abs(u) <= 1)
        d = Vec3(u, 1, 2 - v);
      else if (v < -1 && std::abs(u) <= 1)
        d = Vec3(u, -1, 2 + v);
      else
        continue;
      img.at(px, py) = shade(d);
    }
  return img;
}

Color patch_colour(const Patch& p, std::int32_t item) {
  static const Color surface[7] = {{0.8, 0.8, 0.8}, {0.6, 0.6, 0.7}, {0.8, 0.15, 0.1}, {0.15, 0.7, 0.2},
                                   {0.2, 0.3, 0.8}, {0.8, 0.7, 0.2}, {0.9, 0.5, 0.1}};
  std::uint32_t h = static_cast<std::uint32_t>(item) * 2654435761u;
  h ^= h >> 15;
  const double shade = 0.55 + 0.45 * (h % 1000) / 1000.0;
  return surface[std::clamp(p.surface, 0, 6)] * shade;
}

// --- §2 and §4: pictures of one placement -----------------------------------------------------

// §2. The delta form factors of a 16-pixel hemicube, unfolded.
void draw_delta_form_factors(OutputFolder& out) {
  const int res = 16;
  const HemicubeDeltas deltas = make_hemicube_deltas(res);
  const double top_max = *std::max_element(deltas.top.begin(), deltas.top.end());
  const Image map = unfolded(512, [&](const Vec3& d) {
    HemicubeFace f;
    int col, r;
    if (!hemicube_pixel(d, res, f, col, r)) return Color(1.0);
    const std::size_t p = static_cast<std::size_t>(r) * res + col;
    return colormap_viridis((f == HemicubeFace::top ? deltas.top[p] : deltas.side[p]) / top_max);
  });
  out.image(map, "delta_form_factors",
            "Delta form factors of a 16-pixel hemicube, unfolded, divided by the largest (the top face's "
            "centre): pixels near the normal are worth most; side pixels near the base are worth nothing.");
}

// §4. The five item-buffer faces of one placement on the floor of a room, as false colours per patch.
void draw_item_buffer(OutputFolder& out, bool quick) {
  const auto room = room_with_block(quick ? 6 : 12, quick ? 2 : 4);
  std::size_t receiver = 0;  // the floor patch nearest (0.25, 0.3)
  for (std::size_t j = 0; j < room.size(); ++j)
    if (room[j].surface == 0 && length(room[j].centroid - Point3(0.25, 0.3, 0)) <
                                    length(room[receiver].centroid - Point3(0.25, 0.3, 0)))
      receiver = j;
  const int res = 64;
  const Hemicube hemicube(res);
  HemicubeBuffers buffers;
  std::vector<double> row(room.size());
  // The room's floor normal is +z, so the hemicube's frame is the tangent basis of +z, unrotated.
  hemicube.form_factor_row(room, receiver, row.data(), buffers);
  const Image faces = unfolded(512, [&](const Vec3& d) {
    HemicubeFace f;
    int col, r;
    if (!hemicube_pixel(d, res, f, col, r)) return Color(1.0);
    const std::int32_t item = buffers.face_items(f)[static_cast<std::size_t>(r) * res + col];
    if (item == empty_pixel) return Color(0.0);
    if (item == back_face_pixel) return Color(0.1);
    return patch_colour(room[static_cast<std::size_t>(item)], item);
  });
  out.image(faces, "item_buffer",
            "The five item-buffer faces of one hemicube (64 pixels across) on the floor of a room with a "
            "floating block, unfolded: top face in the middle, side faces folded out; one false colour per "
            "patch (walls tinted by surface).");
}

// --- §5. The hemicube's errors ---------------------------------------------------------------

// The resolutions of the accuracy sweep; the room matrices of §7 quote its errors.
std::vector<int> accuracy_resolutions(bool quick) {
  if (quick) return {4, 8, 16, 32, 64};
  std::vector<int> resolutions;
  for (int r = 4; r <= 64; r += 2) resolutions.push_back(r);
  for (int r : {80, 96, 100, 128, 150, 160, 192, 200, 256, 384, 512}) resolutions.push_back(r);
  return resolutions;
}

// Error from a point against the contour formula, by resolution, with the exact and the notes'
// midpoint deltas. Returns the mean relative error (exact deltas) per resolution.
std::vector<double> accuracy_study(OutputFolder& out, const std::vector<int>& resolutions) {
  struct Config {
    std::string name;
    std::vector<Point3> polygon;
  };
  const std::vector<Config> configs{
      {"near quad", {{0.3, -0.2, 0.5}, {0.1, 0.6, 0.9}, {0.9, 0.9, 1.3}, {1.1, 0.1, 0.9}}},
      {"wall strip", {{0.83, -0.31, 0}, {0.83, -0.31, 0.61}, {0.83, 0.47, 0.61}, {0.83, 0.47, 0}}},
      {"small far square", facing_square(Point3(0.7, 0.4, 2.5), 0.06)}};
  Table accuracy({"config", "rule", "resolution", "hemicube", "exact", "relative_error"});
  std::vector<double> mean_error(resolutions.size(), 0.0);
  for (std::size_t r = 0; r < resolutions.size(); ++r)
    for (const Config& c : configs) {
      const Patch target = facing_origin(c.polygon);
      const std::vector<Patch> patches{receiver_at_origin(), target};
      const double exact = exact_from_origin(target);
      for (DeltaRule rule : {DeltaRule::exact, DeltaRule::midpoint}) {
        if (rule == DeltaRule::midpoint && c.name != "near quad") continue;
        const Hemicube hemicube(resolutions[r], rule);
        HemicubeBuffers buffers;
        double row[2];
        hemicube.form_factor_row(patches, 0, row, buffers);
        const double error = std::abs(row[1] - exact) / exact;
        if (rule == DeltaRule::exact) mean_error[r] += error / configs.size();
        accuracy.add_row({c.name, std::string(rule == DeltaRule::exact ? "exact" : "midpoint"),
                          std::int64_t{resolutions[r]}, row[1], exact, error});
      }
    }
  out.table(accuracy, "accuracy", "Hemicube factor from a point vs Lambert's closed form, by resolution.");
  PlotSpec plot{.title = "Hemicube error vs resolution",
                .x_label = "resolution (pixels across the top face)",
                .y_label = "relative error",
                .log_x = true,
                .log_y = true};
  for (const Config& c : configs)
    plot.curves.push_back({.table = "accuracy.csv",
                           .x = "resolution",
                           .y = "relative_error",
                           .where = {{"config", c.name}, {"rule", "exact"}},
                           .title = c.name + " (exact deltas)"});
  plot.curves.push_back({.table = "accuracy.csv",
                         .x = "resolution",
                         .y = "relative_error",
                         .where = {{"config", "near quad"}, {"rule", "midpoint"}},
                         .title = "near quad (midpoint deltas, the notes)"});
  out.plot(plot, "accuracy",
           "Relative error vs resolution: the small far square's error jumps about "
           "(aliasing); the big patches' error falls roughly as 1/resolution.");
  return mean_error;
}

// A 0.06-wide square at height 2.5 slid sideways at resolution 32, fixed and randomly rotated.
void aliasing_line(OutputFolder& out, bool quick, Rng& rng) {
  const int res = 32;
  const int steps = quick ? 40 : 200;
  Table line({"offset", "fixed_ratio", "rotated_ratio"});
  for (int s = 0; s <= steps; ++s) {
    const double offset = 0.4 * s / steps;
    const Patch square = make_patch(facing_square(Point3(0.5 + offset, 0.3, 2.5), 0.06));
    const std::vector<Patch> patches{receiver_at_origin(), square};
    const double exact = exact_from_origin(square);
    const Hemicube hemicube(res);
    HemicubeBuffers buffers;
    double fixed[2], rotated[2];
    hemicube.form_factor_row(patches, 0, fixed, buffers);
    hemicube.form_factor_row(patches, 0, rotated, buffers, 2 * pi * rng.uniform());
    line.add_row({offset, fixed[1] / exact, rotated[1] / exact});
  }
  out.table(line, "aliasing_line", "A 0.06-wide square at height 2.5 slid sideways: hemicube / exact.");
  const PlotCurve curve{.table = "aliasing_line.csv", .x = "offset"};
  PlotCurve fixed = curve, rotated = curve;
  fixed.y = "fixed_ratio", fixed.title = "fixed orientation";
  rotated.y = "rotated_ratio", rotated.title = "random rotation per estimate",
  rotated.mark = PlotMark::points;
  out.plot({.title = "Small patch slid sideways (resolution 32)",
            .x_label = "offset",
            .y_label = "hemicube / exact",
            .curves = {fixed, rotated}},
           "aliasing_line",
           "Fixed orientation: the estimate jumps between 0 and whole pixels as the patch crosses pixel "
           "centres, the same way every time; a random rotation turns the pattern into noise.");
}

// The small far square: error of the fixed hemicube and of randomly rotated ones, by resolution.
void rotation_study(OutputFolder& out, bool quick, Rng& rng) {
  Table rotation({"resolution", "fixed_error", "rotated_rms_error", "rotated_mean_error"});
  const Patch square = make_patch(facing_square(Point3(0.7, 0.4, 2.5), 0.06));
  const std::vector<Patch> patches{receiver_at_origin(), square};
  const double exact = exact_from_origin(square);
  const int rotations = quick ? 16 : 256;
  for (int res : quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64, 128, 256}) {
    const Hemicube hemicube(res);
    HemicubeBuffers buffers;
    double row[2];
    hemicube.form_factor_row(patches, 0, row, buffers);
    const double fixed = std::abs(row[1] - exact) / exact;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < rotations; ++k) {
      hemicube.form_factor_row(patches, 0, row, buffers, 2 * pi * rng.uniform());
      const double e = (row[1] - exact) / exact;
      sum += row[1];
      sum2 += e * e;
    }
    rotation.add_row(
        {std::int64_t{res}, fixed, std::sqrt(sum2 / rotations), std::abs(sum / rotations - exact) / exact});
  }
  out.table(rotation, "rotation",
            "Small far square: error of the fixed hemicube, RMS error of one randomly rotated estimate, and "
            "error of the mean of all rotated estimates.");
  PlotSpec plot{.title = "Random rotation: aliasing becomes noise",
                .x_label = "resolution",
                .y_label = "relative error",
                .log_x = true,
                .log_y = true};
  for (const auto& [column, title] : {std::pair{"fixed_error", "fixed orientation"},
                                      {"rotated_rms_error", "one random rotation (RMS)"},
                                      {"rotated_mean_error", "mean of the random rotations"}})
    plot.curves.push_back({.table = "rotation.csv", .x = "resolution", .y = column, .title = title});
  out.plot(plot, "rotation", "Errors for the small far square with and without random rotation.");
}

// The hemicube placed on each of the receiver's sub-patches, rows weighted by area.
double subdivided_factor(const Hemicube& hemicube, HemicubeBuffers& buffers, const Patch& target,
                         const std::vector<Patch>& parts) {
  double total = 0, area = 0;
  for (const Patch& part : parts) {
    const std::vector<Patch> pair{part, target};
    double row[2];
    hemicube.form_factor_row(pair, 0, row, buffers);
    total += part.area * row[1];
    area += part.area;
  }
  return total / area;
}

// Point sampling: the hemicube measures the factor from the centroid, not the area average.
void point_sampling_study(OutputFolder& out, bool quick) {
  Table near({"configuration", "distance", "area_to_area", "centroid_exact", "hemicube_centroid",
              "hemicube_8x8_average"});
  const Hemicube hemicube(quick ? 64 : 200);
  HemicubeBuffers buffers;
  const auto receiver_parts =
      mesh_quad({-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}, 8, 8, Color(0.5));
  const Patch receiver = receiver_at_origin(0.5);
  const auto add = [&](const std::string& name, double distance, const Patch& target, double area_to_area,
                       double centroid_exact) {
    const std::vector<Patch> pair{receiver, target};
    double row[2];
    hemicube.form_factor_row(pair, 0, row, buffers);
    near.add_row({name, distance, area_to_area, centroid_exact, row[1],
                  subdivided_factor(hemicube, buffers, target, receiver_parts)});
  };
  for (double h : {0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0}) {
    const Patch target = make_patch({{-0.5, -0.5, h}, {-0.5, 0.5, h}, {0.5, 0.5, h}, {0.5, -0.5, h}});
    // Howell C-11 (directly opposed unit squares), from the library's corner sums.
    const double area_to_area = axis_aligned_rectangles_form_factor(receiver, target);
    if (h == 1.0) require(std::abs(area_to_area - 0.19982) < 1e-4, "C-11 closed form check failed");
    add("parallel squares", h, target, area_to_area, 4 * parallel_corner(0.5, 0.5, h));
  }
  // Two unit squares at right angles sharing an edge: 0.2000438 (Howell C-14 with X = Y = 1).
  const Patch wall = make_patch({{0.5, -0.5, 0}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {0.5, 0.5, 0}});
  add("perpendicular, shared edge", 0.0, wall, 0.2000438, 2 * perpendicular_corner(1, 0.5, 0.5));
  out.table(near, "point_sampling",
            "Unit squares: the exact area-to-area factor, the exact factor from the receiver's centroid, the "
            "hemicube at the centroid, and the hemicube averaged over 8 × 8 sub-patches.",
            5);
  PlotSpec plot{.title = "Point sampling fails for near patches (parallel unit squares)",
                .x_label = "distance",
                .y_label = "form factor",
                .log_x = true};
  for (const auto& [column, title] : {std::pair{"area_to_area", "exact, area to area"},
                                      {"hemicube_centroid", "hemicube at the centroid"},
                                      {"hemicube_8x8_average", "hemicube on 8x8 sub-patches"}})
    plot.curves.push_back({.table = "point_sampling.csv",
                           .x = "distance",
                           .y = column,
                           .where = {{"configuration", "parallel squares"}},
                           .title = title});
  out.plot(plot, "point_sampling", "Near patches: the centroid's factor overestimates the area average.");
}

// --- §6. The price: error against resolution and time -------------------------------------------

// The configurations with exact factors the resolution study sweeps.
std::vector<StudyCase> resolution_study_cases(bool quick) {
  std::vector<StudyCase> cases;
  // A large parallel rectangle [−0.4, 0.8] × [−0.3, 0.6] at height 0.5: Howell's B-3 for the four
  // rectangles that meet above the receiver. Turning it about the normal leaves the factor unchanged
  // but decides whether its edges run along the pixel rows of the top face.
  auto parallel_rectangle = [](const std::string& name, double turn) {
    const double x0 = 0.4, x1 = 0.8, y0 = 0.3, y1 = 0.6, h = 0.5;
    const double exact = parallel_corner(x1, y1, h) + parallel_corner(x0, y1, h) +
                         parallel_corner(x1, y0, h) + parallel_corner(x0, y0, h);
    std::vector<Point3> polygon{{-x0, -y0, h}, {x1, -y0, h}, {x1, y1, h}, {-x0, y1, h}};
    for (Point3& p : polygon) p = rotate_z(p, turn);
    return point_case(name, polygon, exact);
  };
  cases.push_back(parallel_rectangle("near parallel rectangle", 0.4));
  {
    // A wall 0.9 wide and 0.8 high standing on the receiver's plane at distance 0.6: Howell's B-4
    // for the two rectangles either side of the foot of the perpendicular.
    const double d = 0.6, y0 = 0.5, y1 = 0.4, h = 0.8, turn = 0.3;
    const double exact = perpendicular_corner(h, y0, d) + perpendicular_corner(h, y1, d);
    std::vector<Point3> polygon{{d, -y0, 0}, {d, y1, 0}, {d, y1, h}, {d, -y0, h}};
    for (Point3& p : polygon) p = rotate_z(p, turn);
    cases.push_back(point_case("perpendicular rectangle", polygon, exact));
  }
  // 0.06 wide at distance 2.6: a seventh of a pixel at resolution 32. The contour formula.
  const auto square = facing_square(Point3(0.7, 0.4, 2.5), 0.06);
  cases.push_back(point_case("small far square", square, exact_from_origin(facing_origin(square))));
  cases.push_back(room_row_case(quick ? 4 : 8));
  // The same rectangle unturned: its edges lie along pixel rows and columns, so a whole row of pixels
  // falls in or out at once (plotted without the rotated series, which matches the turned one).
  cases.push_back(parallel_rectangle("near parallel rectangle on pixel rows", 0.0));
  return cases;
}

// One resolution of one case: the time of a placement, the fixed error, and the RMS error of one
// randomly rotated placement and the error of their mean.
struct ResolutionPoint {
  double ns = 0;
  RowError fixed;
  double rotated_rms = 0, rotated_mean = 0;
};

ResolutionPoint measure_resolution(const StudyCase& c, int res, int rotations, double min_seconds, Rng& rng) {
  const std::size_t n = c.patches.size();
  std::vector<double> row(n), mean(n, 0.0);
  const Hemicube hemicube(res);
  HemicubeBuffers buffers;
  ResolutionPoint point;
  hemicube.form_factor_row(c.patches, c.receiver, row.data(), buffers);
  point.fixed = row_error(row, c.exact);
  // One placement, timed on one thread: transform, clip and draw every patch, then read the row.
  point.ns = nanoseconds_per_call(
      [&](std::uint64_t) {
        hemicube.form_factor_row(c.patches, c.receiver, row.data(), buffers);
        do_not_optimize(row[0]);
      },
      min_seconds);
  double sum2 = 0;
  for (int k = 0; k < rotations; ++k) {
    hemicube.form_factor_row(c.patches, c.receiver, row.data(), buffers, 2 * pi * rng.uniform());
    const double e = row_error(row, c.exact).mean_rel;
    sum2 += e * e;
    for (std::size_t j = 0; j < n; ++j) mean[j] += row[j] / rotations;
  }
  point.rotated_rms = std::sqrt(sum2 / rotations);
  point.rotated_mean = row_error(mean, c.exact).mean_rel;
  return point;
}

// The two plots of the resolution study: error against resolution and against time.
void plot_resolution_study(OutputFolder& out, const std::vector<StudyCase>& cases) {
  PlotSpec by_res{.title = "Hemicube error vs resolution",
                  .x_label = "resolution (pixels across the top face)",
                  .y_label = "mean relative error",
                  .log_x = true,
                  .log_y = true,
                  .width = 1000,
                  .height = 600};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const PlotCurve fixed{.table = "resolution_study.csv",
                          .x = "resolution",
                          .y = "mean_rel_error",
                          .where = {{"config", cases[k].name}},
                          .title = cases[k].name,
                          .colour = static_cast<int>(k + 1)};
    by_res.curves.push_back(fixed);
    if (k + 1 == cases.size()) continue;
    PlotCurve rotated = fixed;
    rotated.y = "rotated_rms_rel_error", rotated.title += ", rotated (RMS)", rotated.dashed = true;
    by_res.curves.push_back(rotated);
  }
  out.plot(by_res, "resolution_study",
           "Mean relative error vs resolution: the large near patches fall steadily, the small far square "
           "jumps about (aliasing); a random rotation turns the jumps into noise of about the same size.");
  PlotSpec by_time = by_res;
  by_time.title = "Hemicube error vs time per placement";
  by_time.x_label = "time per placement (µs, one thread)";
  for (PlotCurve& curve : by_time.curves) curve.x = "microseconds";
  out.plot(by_time, "resolution_study_time",
           "Mean relative error vs the time of one placement: each point is one resolution; the time grows "
           "as resolution² once the pixels dominate.");
}

// Sweeps the resolution for configurations with exact factors and records, per placement, the
// error without and with a random rotation about the normal, and the time.
void resolution_study(OutputFolder& out, const std::string& id, bool quick, std::uint64_t seed) {
  const std::vector<StudyCase> cases = resolution_study_cases(quick);
  const std::vector<int> resolutions = quick ? std::vector<int>{8, 16, 32, 64}
                                             : std::vector<int>{8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256};
  const int rotations = quick ? 8 : 64;
  Table table({"config", "targets", "resolution", "microseconds", "max_abs_error", "mean_abs_error",
               "max_rel_error", "mean_rel_error", "rotated_rms_rel_error", "rotated_mean_rel_error"});
  Table rates({"config", "error_slope_fixed", "error_slope_rotated_rms", "error_slope_rotated_mean",
               "time_slope_res_ge_64"});
  Rng rng(seed, 11);
  const int total = static_cast<int>(cases.size() * resolutions.size());
  int done = 0;
  for (const StudyCase& c : cases) {
    const auto targets = std::count_if(c.exact.begin(), c.exact.end(), [](double f) { return f > 0; });
    std::vector<double> xs, fixed_errors, rms_errors, mean_errors, times;
    for (int res : resolutions) {
      report_progress(id, "resolution study", done++, total);
      const ResolutionPoint p = measure_resolution(c, res, rotations, quick ? 0.002 : 0.03, rng);
      table.add_row({c.name, static_cast<std::int64_t>(targets), std::int64_t{res}, 1e-3 * p.ns,
                     p.fixed.max_abs, p.fixed.mean_abs, p.fixed.max_rel, p.fixed.mean_rel, p.rotated_rms,
                     p.rotated_mean});
      xs.push_back(res);
      fixed_errors.push_back(p.fixed.mean_rel);
      rms_errors.push_back(p.rotated_rms);
      mean_errors.push_back(p.rotated_mean);
      times.push_back(p.ns);
    }
    rates.add_row({c.name, log_log_slope(xs, fixed_errors), log_log_slope(xs, rms_errors),
                   log_log_slope(xs, mean_errors), log_log_slope(xs, times, 64)});
  }
  report_progress(id, "resolution study", total, total);
  out.table(table, "resolution_study",
            "Hemicube rows against exact factors, by resolution: time per placement (one thread, µs), "
            "max and mean absolute and relative error over the patches the receiver sees (fixed "
            "orientation), the RMS of the mean relative error of one randomly rotated placement, and the "
            "mean relative error of the average of " +
                std::to_string(rotations) + " rotated placements.",
            3);
  out.table(rates, "resolution_study_rates",
            "Least-squares log-log slopes against resolution: of the mean relative error (fixed, one "
            "rotated estimate RMS, mean of the rotated), and of the time per placement for resolution ≥ 64.",
            3);
  plot_resolution_study(out, cases);
}

// --- §7. Whole matrices and their time --------------------------------------------------------

// Full matrices of a closed room with a floating block (~2,000 patches), and the time; the error
// column quotes the accuracy study's mean error at the same resolution.
void room_matrices(OutputFolder& out, const std::string& id, bool quick, const std::vector<int>& resolutions,
                   const std::vector<double>& mean_error) {
  const auto room = quick ? room_with_block(4, 1) : room_with_block(18, 3);
  Table timing({"patches", "resolution", "threads", "seconds", "microseconds_per_row", "max_row_sum_error",
                "mean_relative_error_of_three_configs"});
  const std::vector<int> list = quick ? std::vector<int>{16, 32} : std::vector<int>{50, 100, 150, 200};
  for (std::size_t k = 0; k < list.size(); ++k) {
    report_progress(id, "room matrices", static_cast<int>(k), static_cast<int>(list.size()));
    Stopwatch watch;
    const FormFactorMatrix f = hemicube_form_factors(room, list[k]);
    const double seconds = watch.seconds();
    double worst = 0;
    for (std::size_t i = 0; i < f.size(); ++i) worst = std::max(worst, std::abs(f.row_sum(i) - 1));
    double err = std::nan("");
    for (std::size_t r = 0; r < resolutions.size(); ++r)
      if (resolutions[r] == list[k]) err = mean_error[r];
    timing.add_row({static_cast<std::int64_t>(room.size()), std::int64_t{list[k]},
                    std::int64_t{omp_get_max_threads()}, seconds, 1e6 * seconds / room.size(), worst, err});
  }
  report_progress(id, "room matrices", static_cast<int>(list.size()), static_cast<int>(list.size()));
  out.table(timing, "timing",
            "Whole form-factor matrices of a closed room with a floating block: time, and the largest "
            "deviation of a row sum from 1 (the room is closed).");
  out.plot({.title = "Time per hemicube placement",
            .x_label = "resolution",
            .y_label = "microseconds per row",
            .log_x = true,
            .log_y = true,
            .curves = {{.table = "timing.csv",
                        .x = "resolution",
                        .y = "microseconds_per_row",
                        .title = "room with block"}}},
           "timing", "Time per row grows with the pixel count (resolution²) plus a per-patch cost.");
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson10", "The hemicube",
      "Draws a hemicube's five item-buffer faces and its delta form factors, measures the "
      "hemicube's error against closed forms vs resolution and time (fixed and randomly "
      "rotated), aliasing, point sampling near patches, and times full matrices of a 2,000-patch room."};
  return illum::run_program(argc, argv, info, {}, [&](const illum::ProgramOptions& options) {
    using namespace illum;
    OutputFolder out(options.out, info.id, info.title);
    const bool quick = options.quick;
    draw_delta_form_factors(out);  // §2
    draw_item_buffer(out, quick);  // §4
    const std::vector<int> resolutions = accuracy_resolutions(quick);
    const std::vector<double> mean_error = accuracy_study(out, resolutions);  // §5
    Rng rng(options.seed, 10);
    aliasing_line(out, quick, rng);
    rotation_study(out, quick, rng);
    point_sampling_study(out, quick);
    resolution_study(out, info.id, quick, options.seed);          // §6
    room_matrices(out, info.id, quick, resolutions, mean_error);  // §7
    out.finish();
  });
}
