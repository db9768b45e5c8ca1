// Lesson 01: the ray and the sphere — the demonstration.
//
// Loads the shipped scene of spheres, casts one primary ray through every
// pixel against every sphere with the lesson's intersection
// (geometry/sphere.hpp, through io/sphere_scene's preview renderer), writes
// the silhouette, the normals, the depth and a shaded picture, and prints the
// work it counted. Then the studies the text quotes run in its order, one
// file each in studies/ (README.md, "Read in this order").
#include <iostream>

#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/sphere_scene.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson01", "Lesson 01: the ray and the sphere",
      "Renders spheres (silhouette, normals, depth), shows the notes' quadratic failing "
      "in single precision, and measures error and cost of the notes' form against the "
      "stable form in float and double.",
      TimedCores::one};  // every timing on one thread: the main job may run it beside another
  return run_program(argc, argv, info, {}, [&](const ProgramOptions& options) {
    const lesson01::Settings settings{.quick = options.quick, .seed = options.seed};
    OutputFolder out(options.out, info.id, info.title);

    run_section(info.id, "§2 Substituting the ray into the sphere", [&] {
      const SphereScene scene = load_sphere_scene("spheres");  // scenes/spheres.json, compiled in
      const SpherePreview preview =
          render_sphere_preview(scene, settings.quick ? 96 : 0, settings.quick ? 64 : 0);
      out.image(preview.silhouette, "silhouette", "Silhouette: white where a primary ray hits a sphere");
      out.image(preview.normals, "normals", "Outward normals (P − Pc)/r mapped to RGB as (n + 1)/2");
      out.image(preview.depth, "depth",
                "Depth: the ray parameter s of the nearest hit, near bright, far dark");
      out.image(preview.shaded, "shaded",
                "Each sphere's colour times a Lambert term for a fixed light direction");
      out.text("render_counts.txt", preview.counters.summary() + "\n",
               "Work counted while rendering the preview images");
      std::cout << "spheres: " << preview.counters.summary() << "\n";
    });
    run_section(info.id, "§3 Where the textbook formula loses its digits",
                [&] { lesson01::s03_far_sphere(out, settings); });
    run_section(info.id, "§5 The study: accuracy and its price",
                [&] { lesson01::s05_precision(out, settings); });
    out.finish();
  });
}
