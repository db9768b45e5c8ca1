// Lesson 12: vertex colours, substructuring and the final image — the demonstration.
//
// Solves the Cornell box with patches that shoot and elements that receive
// (radiosity/substructuring.hpp), finds which elements share each vertex
// (radiosity/shared_vertex_mesh.hpp), turns element radiosities into vertex
// colours by the three rules (radiosity/vertex_colours.hpp, the exercise:
// the patch's own colour, the average at a vertex, the extrapolation at wall
// edges) and draws the box Gouraud-shaded with each, side by side; prints the
// counts. The studies the text quotes run in its order, one file each in
// studies/ (README.md, "Read in this order").
#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "element_render.hpp"
#include "illum/core/error.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson12 {
namespace {

// Stretches the pictures' contrast, all with one linear map: the 2nd percentile
// of their pixels' brightest channel goes to black, the 98th to white. The
// close-up spans a small range of radiance, and the slope changes that make
// Mach bands are invisible at its own contrast. Returns the two values.
std::pair<double, double> stretch_contrast(std::vector<Image>& images) {
  std::vector<double> values;
  for (const Image& image : images)
    for (const Color& c : image.pixels()) values.push_back(std::max({c.r, c.g, c.b}));
  if (values.empty()) return {0.0, 1.0};
  std::sort(values.begin(), values.end());
  const double low = values[values.size() * 2 / 100], high = values[values.size() * 98 / 100];
  const double scale = high > low ? 1.0 / (high - low) : 1.0;
  for (Image& image : images)
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        Color& c = image.at(x, y);
        c = Color(std::clamp((c.r - low) * scale, 0.0, 1.0), std::clamp((c.g - low) * scale, 0.0, 1.0),
                  std::clamp((c.b - low) * scale, 0.0, 1.0));
      }
  return {low, high};
}

// The box solved (110 mm patches, 2 × 2 elements each), drawn with the three
// vertex-colour rules side by side, and a close-up of the Mach bands along
// the wall–floor edges; the vertex values of each rule. Prints the counts.
void vertex_colours(OutputFolder& out, const Settings& settings) {
  const Solved s = solve(settings, settings.quick ? 250.0 : 110.0, 2,
                         {.unshot_fraction = settings.quick ? 1e-2 : settings.unshot});
  const int size = settings.quick ? 64 : 256;
  const double exposure = exposure_for(s.mesh, s.solution.element_radiosity);
  const ElementView view = view_elements(s.scene, s.mesh, *s.scene.camera, size, size);
  // The close-up: where the floor meets the red wall, halfway back, clear of both blocks.
  const RadiosityCamera close{
      .eye = s.scene.camera->eye, .target = {551, 0, 250}, .up = {0, 1, 0}, .vertical_fov_degrees = 9};
  const ElementView zoom = view_elements(s.scene, s.mesh, close, size, size);
  std::vector<Image> whole, closeups;
  Table table({"rule", "vertices", "vertices with a channel clamped at 0", "smallest vertex channel"});
  const std::vector<Color> average = average_vertex_radiosity(s.shared, s.solution.element_radiosity);
  const std::vector<Color> extrapolated =
      extrapolated_vertex_radiosity(s.shared, s.solution.element_radiosity);
  for (const auto& [rule, name] : rules) {
    const auto corners = corner_radiosity(s.shared, s.solution.element_radiosity, rule);
    whole.push_back(gouraud_image(view, s.mesh, corners, exposure));
    closeups.push_back(gouraud_image(zoom, s.mesh, corners, exposure));
    std::int64_t clamped = 0;
    double smallest = INFINITY;
    for (std::size_t v = 0; v < s.shared.positions.size(); ++v) {
      const Color& value = rule == VertexColourRule::extrapolate ? extrapolated[v] : average[v];
      smallest = std::min({smallest, value.r, value.g, value.b});
      bool any_clamped = false;  // a vertex counts once, however many channels were clamped
      if (rule == VertexColourRule::extrapolate)
        for (int c = 0; c < 3; ++c) any_clamped |= value[c] == 0 && average[v][c] > 0;
      clamped += any_clamped ? 1 : 0;
    }
    table.add_row({name, static_cast<std::int64_t>(s.shared.positions.size()), clamped, smallest});
  }
  out.image(side_by_side(whole, Color(1.0)), "vertex_rules",
            "The solved box (" + std::to_string(s.mesh.elements.size()) +
                " elements): the patch's own colour, the average at each vertex, the extrapolation "
                "at wall edges (left to right)");
  const auto [low, high] = stretch_contrast(closeups);
  out.image(side_by_side(closeups, Color(1.0)), "mach_bands",
            "Close-up of the floor along the red wall, same three rules, its contrast stretched (linear "
            "radiance " +
                fixed(low, 3) + " to " + fixed(high, 3) +
                " of the exposed picture shown black to "
                "white): flat tiles, then Gouraud, whose slope breaks at every element edge (Mach bands)");
  out.table(table, "vertex_rules", "Vertex values of each rule; the extrapolation's clamps at zero");
  std::cout << s.scene.name << ": " << s.scene.patches.size() << " patches shoot, " << s.mesh.elements.size()
            << " elements receive, " << s.shared.positions.size() << " shared vertices, " << s.solution.shots
            << " shots\n";
}

// The options, each checked before anything is written.
void add_options(CommandLine& command_line, Settings& settings) {
  command_line.add("--scene", settings.scene, "A radiosity scene: a JSON file, or a shipped scene's name")
      .check(path_value())
      .show_default();
  command_line
      .add("--threshold", settings.threshold,
           "subdivision threshold: split where neighbours differ by more than this fraction of the "
           "brightest element (> 0)")
      .check(ValueCheck(
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
      .show_default();
  command_line
      .add("--ply", settings.ply, "also write the figure's binary PLY to this file (its folder must exist)")
      .check(file_in_existing_folder("--ply"));
  const Option elements =
      command_line.add("--elements", settings.figure_elements, "the figure's element count (about)")
          .check(range(100, 200000))
          .show_default();
  const Option edge =
      command_line.add("--patch-edge", settings.figure_patch_edge, "the figure's largest patch edge (mm)")
          .check(number_range(20.0, 1000.0))
          .show_default();
  command_line.add_flag("--figure", settings.figure_only,
                        "only the figure (section 7) and its export (section 8)");
  const Option unshot = command_line
                            .add("--unshot", settings.unshot,
                                 "stop when the unshot power is below this fraction of the emitted")
                            .check(number_range(1e-6, 0.5))
                            .show_default();
  // --quick fixes all three (400 elements, 250 mm patches, 1e-2 unshot): with it, they would be ignored.
  command_line.exclude_quick({elements, edge, unshot});
}

}  // namespace
}  // namespace illum::lesson12

int main(int argc, char** argv) {
  using namespace illum;
  using namespace illum::lesson12;
  const ProgramInfo info{
      program_id, "Vertex colours, substructuring and the final image",
      "The Cornell box drawn with the patch's own colour, averaged and extrapolated vertex "
      "colours; uniform against adaptive substructuring; the box at about 10,000 elements; "
      "PLY and OBJ export.",
      TimedCores::one};  // one thread, unless --threads 2 or more (the main job passes none)
  Settings settings;
  return run_program(
      argc, argv, info, [&](CommandLine& command_line) { add_options(command_line, settings); },
      [&](const ProgramOptions& options) {
        settings.quick = options.quick;
        settings.threads = options.threads;
        const RadiosityScene scene = load_radiosity_scene(settings.scene, 250.0);  // validate before writing
        require_camera_and_light(scene, settings.scene, "lesson 12");
        for (const RadiositySurface& s : scene.surfaces)
          if (s.polygon.size() != 3 && s.polygon.size() != 4)
            throw InputError(settings.scene, "surfaces", s.name, "lesson 12 splits triangles and quads only");
        OutputFolder out(options.out, info.id, info.title);
        if (!settings.figure_only) {
          run_section(info.id, "§3 Extrapolation at the edges and corners of a wall",
                      [&] { vertex_colours(out, settings); });
          run_section(info.id, "§6 The study: uniform against adaptive",
                      [&] { s06_substructuring(out, settings); });
        }
        const Solved figure = run_section(info.id, "§7 The figure: about 10,000 elements",
                                          [&] { return s07_figure(out, settings); });
        run_section(info.id, "§8 Export: PLY and OBJ", [&] { s08_export(out, settings, figure); });
        out.finish();
      });
}
