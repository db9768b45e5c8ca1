// Lesson 04: CSG by combining ray intervals — the demonstration.
//
// Three classic CSG solids (a die, a lens, a drilled cube; solids.hpp) traced
// through the pinhole camera by the notes' three lines: intersect the ray
// with the primitives, combine their intervals by the tree's Boolean
// operations, take the nearest crossing (geometry/csg_tree.hpp, with the
// lesson's merge in geometry/span_combine.hpp). Writes each shaded and as
// normals, and prints the work counted. The studies the text quotes run in
// its order, one file each in studies/ (README.md, "Read in this order").
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/geometry/csg_tree.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "solids.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson04 {
namespace {

using Shader = std::function<Color(const Ray&, const CsgHit&)>;

// One primary ray per pixel through the tree: intersect (geometry/csg_tree.hpp)
// evaluates the primitives' spans, combines them by the tree's operations and
// takes the nearest crossing. Counters per thread, added up at the end.
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

// The three solids, shaded and as normals, and the work counted while drawing them.
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
  std::cout << "gallery: " << counters.work.summary() << "\n";
}

}  // namespace
}  // namespace illum::lesson04

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson04", "CSG by combining ray intervals",
      "Renders a die, a lens and a drilled cube built by CSG, then measures coincident-face "
      "artefacts against the sliver tolerance and cost against tree depth with and without "
      "bounding-box pruning.",
      TimedCores::one};  // every timing on one thread: the main job may run it beside another
  return run_program(argc, argv, info, {}, [&](const ProgramOptions& options) {
    const lesson04::Settings settings{.quick = options.quick};
    OutputFolder out(options.out, info.id, info.title);
    run_section(info.id, "§6 The nearest crossing is the hit", [&] {
      lesson04::render_gallery(out, settings.quick ? 120 : 480, settings.quick ? 90 : 360);
    });
    run_section(info.id, "§8 Study: coincident-face artefacts",
                [&] { lesson04::s08_coincident_faces(out, settings); });
    run_section(info.id, "§9 Study: cost against tree depth",
                [&] { lesson04::s09_depth_cost(out, settings); });
    out.finish();
  });
}
