// Lesson 08: spatial structures — the demonstration.
//
// Builds a deterministic sphereflake of about 10⁵ triangles
// (accel/sphereflake.hpp), puts its triangles into the structure --accel names
// (accel/triangle_accel.hpp: the BVH by default; `--accel bvh` runs
// the exercise's traversal, bvh_traversal.cpp, as a student's code would),
// renders it with a shadow ray per lit sample, writes the picture and prints
// the nodes visited and the triangles tested. The studies the text quotes run
// in its order, one file each in studies/ (README.md, "Read in this order").
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "flakes.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/whole_machine.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace {

// The demonstration: the sphereflake through the chosen structure, on every thread; then the
// thread study of §6 on the same picture. Both with the machine to themselves: every study before
// them times one thread, and the main job runs the program beside others until it gets here.
void render_demonstration(illum::OutputFolder& out, const illum::lesson08::Settings& settings) {
  using namespace illum;
  using namespace lesson08;
  const WholeMachine machine;
  const TriangleSet set = flake_with_about(settings.quick ? 5000 : 100000);
  const std::unique_ptr<TriangleAccel> structure = make_accel(set, {.kind = settings.accel});
  const PictureSize size = picture_size(settings.quick);
  const FlakePicture picture =
      render_flake(*structure, flake_camera(size.width, size.height), size.side, available_threads());
  const TraversalCounters& c = picture.counters;
  out.image(picture.image, "sphereflake",
            "A sphereflake of " + std::to_string(set.size()) + " triangles through the " +
                (settings.accel == AccelKind::compact_bvh ? std::string("BVH") : to_string(settings.accel)) +
                ", with a shadow ray per lit pixel");
  const std::string counts = "rays " + std::to_string(c.rays) + "; nodes visited " +
                             std::to_string(c.nodes_visited) + "; triangle tests " +
                             std::to_string(c.triangle_tests) + "; triangles " + std::to_string(set.size()) +
                             "; degenerate faces left out " + std::to_string(set.degenerate.size());
  out.text("render_counts.txt", counts + "\n", "Work counted while rendering the sphereflake");
  std::cout << "sphereflake through " << structure->name() << ": " << counts << "\n";

  s06e_render_threads(out, settings, *structure, picture.image);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      lesson08::program_id, "Spatial structures",
      "Measures brute force, the uniform grid (3DDA) and the BVH (binned SAH) on sphereflakes of 10^2 to "
      "10^6 triangles: cells or nodes and triangle tests per ray, throughput, build time and memory; "
      "sweeps the grid resolution and the BVH leaf size; renders with 1 and 2 threads; times the "
      "teaching and production BVHs and the Monte Carlo form factors with and without the BVH.",
      TimedCores::mixed};  // one thread, but for the demonstration and its thread study (WholeMachine)
  lesson08::Settings settings;
  std::string structure_name = to_string(settings.accel);
  std::vector<std::string> structures;
  for (const AccelKind kind : all_accel_kinds) structures.emplace_back(to_string(kind));
  return run_program(
      argc, argv, info,
      [&](CommandLine& command_line) {
        command_line
            .add("--accel", structure_name,
                 "the structure the sphereflake is rendered through: compact_bvh (production, the default), "
                 "bvh (the exercise's traversal), grid, octree or brute_force")
            .check(one_of(structures))
            .show_default();
      },
      [&](const ProgramOptions& options) {
        using namespace lesson08;
        settings.quick = options.quick;
        settings.accel = accel_kind_from_name(structure_name);
        OutputFolder out(options.out, info.id, info.title);
        run_section(info.id, "§1 Visibility algorithms", [&] {
          s01_item_buffer(out, settings);
          s01_light_buffer(out, settings);
        });
        run_section(info.id, "§2 Bounding volumes and the slab test",
                    [&] { s02_bounding_volumes(out, settings); });
        run_section(info.id, "§5 Bounding volume hierarchies", [&] { s05_bvh_layouts(out, settings); });
        run_section(info.id, "§6 The measurements", [&] {
          s06a_scaling(out, settings);
          s06b_grid_resolution(out, settings);
          s06c_bvh_leaf_size(out, settings);
          s06d_octree_depth(out, settings);

          render_demonstration(out, settings);
        });
        run_section(info.id, "§8 The structures at work elsewhere in the course",
                    [&] { s08_form_factor_visibility(out, settings); });
        out.finish();
      });
}
