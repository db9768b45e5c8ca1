// Lesson 12: vertex colours, substructuring and the final image. Solves the
// Cornell box with patches that shoot and elements that receive, draws it
// with the three vertex-colour rules side by side (and a close-up of the
// Mach bands along the wall–floor edges), studies uniform against adaptive
// subdivision (error against a uniformly fine solution, and time, per
// element count), solves the box at about 10,000 elements with both
// visibility methods, and exports the result as PLY and OBJ.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <string>
#include <variant>
#include <vector>

#include <omp.h>
#include <CLI/CLI.hpp>

#include "element_render.hpp"
#include "illum/core/atomic_file.hpp"
#include "illum/core/error.hpp"
#include "illum/io/cli_checks.hpp"
#include "illum/io/mesh_export.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/element_subdivision.hpp"
#include "illum/radiosity/shared_vertex_mesh.hpp"
#include "illum/radiosity/substructuring.hpp"
#include "illum/radiosity/vertex_colours.hpp"

namespace illum {
namespace {

const char* program_id = "lesson12";

// What the command line sets (validated there, before anything is written).
struct Settings {
  std::string scene = "cornell";
  bool quick = false;
  double threshold = 0.05;        // subdivision: a gap above this fraction of the brightest element splits
  std::filesystem::path ply;      // --ply: also write the figure's binary PLY here
  int figure_elements = 10000;    // the figure's element count (about)
  double figure_patch_edge = 75;  // mm: the figure's patches (the shooters)
  double unshot = 1e-3;           // stop at this fraction of the emitted power unshot
  bool figure_only = false;       // --figure: only the figure (section 7) and its export (section 8)
};

// "ray_cast_bvh_1_threads" → "ray cast bvh 1 threads" (gnuplot reads '_' as a subscript).
std::string spaced(std::string text) {
  std::replace(text.begin(), text.end(), '_', ' ');
  return text;
}

std::string fixed(double value, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, value);
  return b;
}

const std::vector<std::pair<VertexColourRule, std::string>> rules = {
    {VertexColourRule::patch_own, "patch_own"},
    {VertexColourRule::average, "average"},
    {VertexColourRule::extrapolate, "extrapolate"}};

// A solved element mesh: the scene, its elements, their radiosity and who shares which vertex.
struct Solved {
  RadiosityScene scene;
  ElementMesh mesh;
  SubstructuredSolution solution;
  SharedVertexMesh shared;
};

// The scene's surfaces block light for the ray-cast rows (a few dozen
// triangles in the BVH instead of two per patch).
ShootingSettings with_occluders(ShootingSettings shooting, const RadiosityScene& scene) {
  for (const RadiositySurface& surface : scene.surfaces) shooting.occluders.push_back(surface.polygon);
  return shooting;
}

Solved solve(const Settings& settings, double patch_edge, int k, const ShootingSettings& shooting) {
  Solved s;
  s.scene = load_radiosity_scene(settings.scene, patch_edge);
  s.mesh = uniform_elements(s.scene.patches, k);
  s.solution = shoot_patches_to_elements(s.scene.patches, s.mesh, with_occluders(shooting, s.scene));
  s.shared = share_vertices(s.mesh.elements);
  return s;
}

// --- 1–3. Vertex colours: the three rules side by side, and the Mach bands ----
Solved vertex_colour_section(OutputFolder& out, const Settings& settings) {
  const Solved s = solve(settings, settings.quick ? 250.0 : 110.0, 2,
                         {.unshot_fraction = settings.quick ? 1e-2 : settings.unshot});
  const int size = settings.quick ? 64 : 256;
  const double exposure = lesson12::exposure_for(s.mesh, s.solution.element_radiosity);
  const lesson12::ElementView view = lesson12::view_elements(s.scene, s.mesh, *s.scene.camera, size, size);
  // The close-up: the back wall's lower left corner, where the red wall and the floor meet it.
  const RadiosityCamera close{
      .eye = s.scene.camera->eye, .target = {500, 40, 559}, .up = {0, 1, 0}, .vertical_fov_degrees = 9};
  const lesson12::ElementView zoom = lesson12::view_elements(s.scene, s.mesh, close, size, size);
  std::vector<Image> whole, closeups;
  Table table({"rule", "vertices", "vertices with a channel clamped at 0", "smallest vertex channel"});
  const std::vector<Color> average = average_vertex_radiosity(s.shared, s.solution.element_radiosity);
  const std::vector<Color> extrapolated =
      extrapolated_vertex_radiosity(s.shared, s.solution.element_radiosity);
  for (const auto& [rule, name] : rules) {
    const auto corners = corner_radiosity(s.shared, s.solution.element_radiosity, rule);
    whole.push_back(lesson12::gouraud_image(view, s.mesh, corners, exposure));
    closeups.push_back(lesson12::gouraud_image(zoom, s.mesh, corners, exposure));
    std::int64_t clamped = 0;
    double smallest = INFINITY;
    for (std::size_t v = 0; v < s.shared.positions.size(); ++v) {
      const Color& value = rule == VertexColourRule::extrapolate ? extrapolated[v] : average[v];
      smallest = std::min({smallest, value.r, value.g, value.b});
      if (rule == VertexColourRule::extrapolate)
        for (int c = 0; c < 3; ++c) clamped += value[c] == 0 && average[v][c] > 0 ? 1 : 0;
    }
    table.add_row({name, static_cast<std::int64_t>(s.shared.positions.size()), clamped, smallest});
  }
  out.image(lesson12::side_by_side(whole), "vertex_rules",
            "The solved box (" + std::to_string(s.mesh.elements.size()) +
                " elements): the patch's own colour, the average at each vertex, the extrapolation "
                "at wall edges (left to right)");
  out.image(lesson12::side_by_side(closeups), "mach_bands",
            "Close-up of the back wall's lower left corner, same three rules: flat tiles, then Gouraud "
            "with its Mach bands along the element edges");
  out.table(table, "vertex_rules", "Vertex values of each rule; the extrapolation's clamps at zero");
  return s;
}

// The errors of `s` against the fine reference, per rule (flat = own,
// average, extrapolate), over the reference's non-emitting, lit elements r with
// the solution read at r's centroid x_r:
//   mean: Σ A_r |B(x_r) − B_r| / Σ A_r B_r      (channels summed)
//   max:  max_r max_c |B(x_r) − B_r| / max_r max_c B_r
struct Errors {
  double mean[3] = {0, 0, 0}, max[3] = {0, 0, 0};
};

Errors errors_against(const Solved& s, const Solved& reference) {
  std::vector<std::vector<int>> elements_of(s.scene.patches.size());
  for (std::size_t e = 0; e < s.mesh.elements.size(); ++e)
    elements_of[static_cast<std::size_t>(s.mesh.patch_of[e])].push_back(static_cast<int>(e));
  Errors errors;
  for (std::size_t rule = 0; rule < rules.size(); ++rule) {
    const auto corners = corner_radiosity(s.shared, s.solution.element_radiosity, rules[rule].first);
    double difference = 0, total = 0, largest_difference = 0, largest = 0;
    for (std::size_t r = 0; r < reference.mesh.elements.size(); ++r) {
      const Patch& element = reference.mesh.elements[r];
      const Color& b = reference.solution.element_radiosity[r];
      // Emitters, and elements that receive nothing (hidden from every
      // patch, so from any eye in the scene: the ceiling above the light, the
      // floor under the blocks), are left out.
      if (element.emission.r + element.emission.g + element.emission.b > 0 || b == Color(0.0)) continue;
      for (int e : elements_of[static_cast<std::size_t>(reference.mesh.patch_of[r])]) {
        const auto ue = static_cast<std::size_t>(e);
        if (!lesson12::element_contains(s.mesh.elements[ue], element.centroid)) continue;
        const Color d =
            glm::abs(interpolate_radiosity(s.mesh.elements[ue], corners[ue], element.centroid) - b);
        difference += element.area * (d.r + d.g + d.b);
        total += element.area * (b.r + b.g + b.b);
        largest_difference = std::max({largest_difference, d.r, d.g, d.b});
        largest = std::max({largest, b.r, b.g, b.b});
        break;
      }
    }
    errors.mean[rule] = difference / total;
    errors.max[rule] = largest_difference / largest;
  }
  return errors;
}

// Adaptive substructuring: solve, split where neighbours differ by more than
// the threshold (a fraction of the brightest non-emitting element), solve
// again, until nothing splits or the elements reach min_edge.
Solved adaptive(const Settings& settings, double patch_edge, double threshold, double min_edge,
                const ShootingSettings& shooting, double& seconds) {
  Solved s = solve(settings, patch_edge, 1, shooting);
  seconds = s.solution.seconds;
  for (int level = 0; level < 6; ++level) {
    double brightest = 0;
    for (std::size_t e = 0; e < s.mesh.elements.size(); ++e)
      if (s.mesh.elements[e].emission == Color(0.0))
        brightest = std::max({brightest, s.solution.element_radiosity[e].r, s.solution.element_radiosity[e].g,
                              s.solution.element_radiosity[e].b});
    const std::vector<bool> split = elements_to_split(s.shared.neighbours, s.solution.element_radiosity,
                                                      longest_edges(s.mesh), threshold * brightest, min_edge);
    if (std::find(split.begin(), split.end(), true) == split.end()) break;
    s.mesh = split_elements(s.mesh, split);
    s.solution = shoot_patches_to_elements(s.scene.patches, s.mesh, with_occluders(shooting, s.scene));
    s.shared = share_vertices(s.mesh.elements);
    seconds += s.solution.seconds;
  }
  return s;
}

// The element count at which the uniform runs (elements, error), in order of
// elements, reach `error`: linear interpolation of log error against log
// elements between the first two runs that bracket it; outside their range,
// the text "more than" the largest run (no uniform run was that accurate)
// or "fewer than" the smallest.
Table::Cell uniform_elements_at(const std::vector<std::pair<double, double>>& runs, double error) {
  double lowest = INFINITY;
  for (std::size_t i = 1; i < runs.size(); ++i) {
    const auto [n0, e0] = runs[i - 1];
    const auto [n1, e1] = runs[i];
    lowest = std::min({lowest, e0, e1});
    if (!(error <= std::max(e0, e1) && error >= std::min(e0, e1)) || e0 == e1) continue;
    const double f = std::log(error / e0) / std::log(e1 / e0);
    return std::exp(std::log(n0) + f * std::log(n1 / n0));
  }
  const auto count = [](double n) { return std::to_string(static_cast<long long>(n)); };
  return error < lowest ? "more than " + count(runs.back().first) : "fewer than " + count(runs.front().first);
}

// --- 6. The study's plots: error and time against element count -------------
void study_plots(OutputFolder& out) {
  const auto curve = [](const std::string& y, const std::string& scheme, const std::string& title,
                        bool dashed) {
    return PlotCurve{.table = "substructuring.csv",
                     .x = "elements",
                     .y = y,
                     .where = {{"scheme", scheme}},
                     .title = title,
                     .dashed = dashed};
  };
  out.plot({.title = "Substructuring: error against element count (flat elements)",
            .x_label = "elements",
            .y_label = "relative error",
            .log_x = true,
            .log_y = true,
            .curves = {curve("flat_max_error", "uniform", "uniform, largest error", false),
                       curve("flat_max_error", "adaptive", "adaptive, largest error", false),
                       curve("flat_mean_error", "uniform", "uniform, mean error", true),
                       curve("flat_mean_error", "adaptive", "adaptive, mean error", true)}},
           "substructuring_error", "Largest and mean error against element count, uniform and adaptive");
  out.plot({.title = "Substructuring: time against element count",
            .x_label = "elements",
            .y_label = "seconds",
            .log_x = true,
            .log_y = true,
            .curves = {{.table = "substructuring.csv",
                        .x = "elements",
                        .y = "seconds",
                        .where = {{"scheme", "uniform"}},
                        .title = "uniform"},
                       {.table = "substructuring.csv",
                        .x = "elements",
                        .y = "seconds",
                        .where = {{"scheme", "adaptive"}},
                        .title = "adaptive (every pass)"}}},
           "substructuring_time", "Solve time against element count, uniform and adaptive");
}

// --- 5–6. Uniform against adaptive substructuring ------------------------------
void substructuring_study(OutputFolder& out, const Settings& settings) {
  const double patch_edge = settings.quick ? 275.0 : 140.0;
  const int reference_k = settings.quick ? 4 : 16;
  const ShootingSettings shooting{.unshot_fraction = settings.quick ? 1e-2 : 1e-3};
  // On one thread, like lesson 11's study: the seconds compare the methods'
  // work, not how a loaded machine schedules two threads' barriers.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  report_progress(program_id, "study: the uniformly fine reference", 0, 1);
  const Solved reference = solve(settings, patch_edge, reference_k, shooting);
  Table table({"scheme", "knob", "patches", "elements", "shots", "seconds", "flat_mean_error",
               "average_mean_error", "extrapolated_mean_error", "flat_max_error", "extrapolated_max_error"});
  std::vector<std::pair<double, double>> uniform_mean, uniform_max;  // (elements, flat error)
  Table equal({"threshold", "adaptive elements", "flat_max_error", "uniform elements at that max error",
               "flat_mean_error", "uniform elements at that mean error"});
  const auto add = [&](const std::string& scheme, const std::string& knob, const Solved& s, double seconds) {
    const Errors e = errors_against(s, reference);
    const auto elements = static_cast<double>(s.mesh.elements.size());
    if (scheme == "uniform") {
      uniform_mean.push_back({elements, e.mean[0]});
      uniform_max.push_back({elements, e.max[0]});
    } else {
      equal.add_row({knob, static_cast<std::int64_t>(elements), e.max[0],
                     uniform_elements_at(uniform_max, e.max[0]), e.mean[0],
                     uniform_elements_at(uniform_mean, e.mean[0])});
    }
    table.add_row({scheme, knob, static_cast<std::int64_t>(s.scene.patches.size()),
                   static_cast<std::int64_t>(s.mesh.elements.size()),
                   static_cast<std::int64_t>(s.solution.shots), seconds, e.mean[0], e.mean[1], e.mean[2],
                   e.max[0], e.max[2]});
  };
  for (int k : settings.quick ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 3, 4, 6, 8}) {
    report_progress(program_id, "study: uniform k = " + std::to_string(k), k, 8);
    const Solved s = solve(settings, patch_edge, k, shooting);
    add("uniform", std::to_string(k) + "x" + std::to_string(k), s, s.solution.seconds);
  }
  const std::vector<double> thresholds = settings.quick ? std::vector<double>{settings.threshold}
                                                        : std::vector<double>{0.2, 0.1, 0.05, 0.025, 0.0125};
  for (double t : thresholds) {
    report_progress(program_id, "study: adaptive, threshold " + fixed(t, 4), 0, 1);
    double seconds = 0;
    const Solved s = adaptive(settings, patch_edge, t, patch_edge / reference_k * 1.01, shooting, seconds);
    add("adaptive", fixed(t, 4), s, seconds);
  }
  out.table(table, "substructuring",
            "Uniform and adaptive substructuring of the box (" +
                std::to_string(reference.scene.patches.size()) + " patches): error against a uniform " +
                std::to_string(reference_k) + "x" + std::to_string(reference_k) + " solution (" +
                std::to_string(reference.mesh.elements.size()) +
                " elements), and time (adaptive: all its solves)");
  out.table(equal, "equal_error",
            "Elements a uniform mesh needs for each adaptive mesh's flat errors (log-log interpolation "
            "between the uniform runs)");
  omp_set_num_threads(threads);
  study_plots(out);
}

// --- 7. The progressive picture: the figure's run at a few unshot levels -----
void progressive_pictures(OutputFolder& out, const Settings& settings, const Solved& s,
                          const std::vector<double>& levels) {
  const int size = settings.quick ? 64 : 256;
  const lesson12::ElementView view = lesson12::view_elements(s.scene, s.mesh, *s.scene.camera, size, size);
  const double exposure = lesson12::exposure_for(s.mesh, s.solution.element_radiosity);
  std::vector<Image> pictures;
  std::string which;
  for (std::size_t i = 0; i < s.solution.snapshots.size(); ++i) {
    pictures.push_back(lesson12::gouraud_image(
        view, s.mesh, corner_radiosity(s.shared, s.solution.snapshots[i], VertexColourRule::extrapolate),
        exposure));
    which += (i ? ", " : "") + fixed(100 * levels[i], 0) + "%";
  }
  pictures.push_back(lesson12::gouraud_image(
      view, s.mesh, corner_radiosity(s.shared, s.solution.element_radiosity, VertexColourRule::extrapolate),
      exposure));
  out.image(lesson12::side_by_side(pictures), "figure_progressive",
            "The figure's run when the unshot power first fell below " + which +
                " of the emitted (ambient term added for display), and at the end");
}

// --- 7. The figure: the box at about 10,000 elements, both visibility methods ---
Solved figure_section(OutputFolder& out, const Settings& settings) {
  const double edge = settings.quick ? 250.0 : settings.figure_patch_edge;
  const std::size_t patches = load_radiosity_scene(settings.scene, edge).patches.size();
  const int target = settings.quick ? 400 : settings.figure_elements;
  const int k = std::max(1, static_cast<int>(std::lround(std::sqrt(target / static_cast<double>(patches)))));
  Table figure({"visibility", "patches", "elements", "threads", "shots", "unshot / emitted", "seconds",
                "processor seconds (all threads)"});
  Table tenths({"run", "tenth", "shots", "seconds", "unshot_fraction"});
  Solved kept;
  const int threads = omp_get_max_threads();
  const std::vector<double> snapshot_levels = {0.5, 0.1, 0.01};
  // Each method on one thread and on all: on a machine loaded by other work
  // a thread waits at every shot's barrier for its partner.
  for (const auto& [visibility, name] : {std::pair{ShotVisibility::ray_cast, "ray_cast_bvh"},
                                         std::pair{ShotVisibility::hemicube, "hemicube_128"}})
    for (const int t : threads > 1 ? std::vector<int>{1, threads} : std::vector<int>{1}) {
      report_progress(program_id, std::string("figure: ") + name + ", " + std::to_string(t) + " threads", 0,
                      1);
      omp_set_num_threads(t);
      // Processor time of every thread: other programs' load does not inflate it.
      const std::clock_t cpu_start = std::clock();
      Solved s = solve(settings, edge, k,
                       {.visibility = visibility,
                        .unshot_fraction = settings.quick ? 1e-2 : settings.unshot,
                        .snapshot_unshot = snapshot_levels});
      const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      omp_set_num_threads(threads);
      const SubstructuredSolution& r = s.solution;
      figure.add_row({std::string(name), static_cast<std::int64_t>(s.scene.patches.size()),
                      static_cast<std::int64_t>(s.mesh.elements.size()), std::int64_t{t},
                      static_cast<std::int64_t>(r.shots), r.unshot_fraction, r.seconds, cpu_seconds});
      const std::string run = std::string(name) + "_" + std::to_string(t) + "_threads";
      for (int tenth = 1; tenth <= 10; ++tenth) {
        const ShotRecord& h = r.history[std::max<std::size_t>(1, (r.history.size() * tenth + 9) / 10) - 1];
        tenths.add_row(
            {run, std::int64_t{tenth}, static_cast<std::int64_t>(h.shots), h.seconds, h.unshot_fraction});
      }
      std::cout << "Figure (" << name << "): " << s.scene.patches.size() << " patches, "
                << s.mesh.elements.size() << " elements, " << r.shots << " shots to "
                << fixed(100 * r.unshot_fraction, 3) << "% unshot in " << fixed(r.seconds, 2) << " s on " << t
                << " threads\n";
      if (visibility == ShotVisibility::ray_cast) kept = std::move(s);
    }
  out.table(figure, "figure", "The box solved to the unshot target: shoot from patches, receive at elements");
  out.table(tenths, "figure_tenths", "Time and unshot power after each tenth of the figure's shots");
  std::vector<PlotCurve> curves;
  for (const auto& row : tenths.rows())
    if (std::get<std::int64_t>(row[1]) == 1)
      curves.push_back({.table = "figure_tenths.csv",
                        .x = "seconds",
                        .y = "unshot_fraction",
                        .where = {{"run", std::get<std::string>(row[0])}},
                        .title = spaced(std::get<std::string>(row[0]))});
  out.plot({.title = "The figure's run: unshot power against time",
            .x_label = "seconds",
            .y_label = "unshot / emitted power",
            .log_y = true,
            .curves = curves},
           "figure_tenths", "Unshot power after each tenth of the run, against the time spent");
  const int size = settings.quick ? 64 : 384;
  const lesson12::ElementView view =
      lesson12::view_elements(kept.scene, kept.mesh, *kept.scene.camera, size, size);
  out.image(lesson12::gouraud_image(
                view, kept.mesh,
                corner_radiosity(kept.shared, kept.solution.element_radiosity, VertexColourRule::extrapolate),
                lesson12::exposure_for(kept.mesh, kept.solution.element_radiosity)),
            "figure", "The figure's box, Gouraud-shaded from extrapolated vertex colours");
  progressive_pictures(out, settings, kept, snapshot_levels);
  return kept;
}

// --- 8. Export: PLY (binary and ASCII) and OBJ with per-vertex colours ----------
void export_section(OutputFolder& out, const Settings& settings, const Solved& s) {
  std::vector<Color> value = extrapolated_vertex_radiosity(s.shared, s.solution.element_radiosity);
  resolve_t_vertices(s.shared, value);
  const double exposure = lesson12::exposure_for(s.mesh, s.solution.element_radiosity);
  ColouredMesh mesh{.positions = s.shared.positions, .colours = {}, .faces = display_polygons(s.shared)};
  for (const Color& v : value)
    mesh.colours.push_back({to_srgb8(exposure * v.r), to_srgb8(exposure * v.g), to_srgb8(exposure * v.b)});
  const std::string comment = "illum lesson 12: " + s.scene.name + ", extrapolated vertex radiosity";
  write_ply_file(out.path("cornell_box.ply"), mesh, PlyEncoding::binary_little_endian, comment);
  out.add_file("mesh", "cornell_box.ply",
               "The solved box, binary PLY with per-vertex colours (MeshLab, Blender)");
  write_ply_file(out.path("cornell_box_ascii.ply"), mesh, PlyEncoding::ascii, comment);
  out.add_file("mesh", "cornell_box_ascii.ply", "The same mesh as ASCII PLY");
  write_obj_file(out.path("cornell_box.obj"), mesh, comment);
  out.add_file("mesh", "cornell_box.obj", "The same mesh as OBJ with vertex colours (v x y z r g b)");
  if (!settings.ply.empty()) write_ply_file(settings.ply, mesh, PlyEncoding::binary_little_endian, comment);
  std::cout << "Export: " << mesh.positions.size() << " vertices, " << mesh.faces.size() << " faces\n";
}

// The options, each checked before anything is written.
void add_options(CLI::App& app, Settings& settings) {
  app.add_option("--scene", settings.scene, "A radiosity scene: a JSON file, or a shipped scene's name")
      ->capture_default_str();
  app.add_option("--threshold", settings.threshold,
                 "subdivision threshold: split where neighbours differ by more than this fraction of the "
                 "brightest element (> 0)")
      ->check(CLI::Validator(
          [](std::string& text) {
            double value = NAN;
            try {
              value = std::stod(text);
            } catch (const std::exception&) {
              return "'" + text + "' is not a number";
            }
            return value > 0 && value <= 1
                       ? std::string()
                       : "the subdivision threshold " + text +
                             " must be positive and at most 1 (a fraction of the brightest "
                             "element)";
          },
          "THRESHOLD"))
      ->capture_default_str();
  app.add_option("--ply", settings.ply,
                 "also write the figure's binary PLY to this file (its folder must exist)")
      ->check(CLI::Validator(
          [](std::string& path) {
            const std::filesystem::path parent = std::filesystem::path(path).parent_path();
            if (std::filesystem::path(path).filename().empty())
              return std::string("names a folder, not a file");
            if (!parent.empty() && !std::filesystem::is_directory(parent))
              return "the folder " + parent.string() + " does not exist";
            try {  // a device, a FIFO, a link or a folder is never written through or replaced
              check_replaceable(path, "--ply");
            } catch (const std::runtime_error& e) {
              return std::string(e.what());
            }
            return std::string();
          },
          "PLY FILE"));
  CLI::Option* elements =
      app.add_option("--elements", settings.figure_elements, "the figure's element count (about)")
          ->check(CLI::Range(100, 200000))
          ->capture_default_str();
  CLI::Option* edge =
      app.add_option("--patch-edge", settings.figure_patch_edge, "the figure's largest patch edge (mm)")
          ->check(number_range(20.0, 1000.0))
          ->capture_default_str();
  app.add_flag("--figure", settings.figure_only, "only the figure (section 7) and its export (section 8)");
  CLI::Option* unshot = app.add_option("--unshot", settings.unshot,
                                       "stop when the unshot power is below this fraction of the emitted")
                            ->check(number_range(1e-6, 0.5))
                            ->capture_default_str();
  // --quick fixes all three (400 elements, 250 mm patches, 1e-2 unshot): with it, they would be ignored.
  exclude_quick(app, {elements, edge, unshot});
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      program_id, "Vertex colours, substructuring and the final image",
      "The Cornell box drawn with the patch's own colour, averaged and extrapolated vertex "
      "colours; uniform against adaptive substructuring; the box at about 10,000 elements; "
      "PLY and OBJ export."};
  Settings settings;
  return run_program(
      argc, argv, info, [&](CLI::App& app) { add_options(app, settings); },
      [&](const ProgramOptions& options) {
        settings.quick = options.quick;
        const RadiosityScene scene = load_radiosity_scene(settings.scene, 250.0);  // validate before writing
        if (!scene.camera)
          throw InputError(settings.scene, "camera", "(missing)",
                           "lesson 12 draws the scene through its camera");
        double emitted = 0;
        for (const Patch& p : scene.patches) emitted += p.area * (p.emission.r + p.emission.g + p.emission.b);
        if (!(emitted > 0))
          throw InputError(settings.scene, "materials", "(no emission)",
                           "no surface emits light: nothing to solve");
        for (const RadiositySurface& s : scene.surfaces)
          if (s.polygon.size() != 3 && s.polygon.size() != 4)
            throw InputError(settings.scene, "surfaces", s.name, "lesson 12 splits triangles and quads only");
        OutputFolder out(options.out, info.id, info.title);
        if (!settings.figure_only) {
          vertex_colour_section(out, settings);
          substructuring_study(out, settings);
        }
        const Solved figure = figure_section(out, settings);
        export_section(out, settings, figure);
        out.finish();
      });
}
