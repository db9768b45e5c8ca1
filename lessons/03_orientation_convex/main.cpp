// Lesson 03: orientation and convex tests — the demonstration.
//
// A pentagram, a polygon that crosses itself, drawn twice from the same
// oriented crossings: by parity (lesson 02) its centre is a hole, by the
// nonzero winding rule (geometry/winding.hpp, the lesson's) it is filled,
// shaded by the winding number. Writes both pictures and prints the winding
// number at the centre. The studies the text quotes run in its order, one
// file each in studies/ (README.md, "Read in this order").
#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/random.hpp"
#include "illum/geometry/parity.hpp"
#include "illum/geometry/winding.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson03 {
namespace {

using std::numbers::pi;

// The pentagram {5/2}: five vertices on the unit circle, each joined to the
// next but one, so that the outline crosses itself.
Polygon pentagram() {
  std::vector<Vec2> p;
  for (int k = 0; k < 5; ++k)
    p.push_back({std::cos(pi / 2 + k * 4 * pi / 5), std::sin(pi / 2 + k * 4 * pi / 5)});
  return flat(p);
}

// The pentagram on a size × size grid of [−1.1, 1.1]²: inside by the nonzero
// rule (winding ≠ 0) or by parity.
Image pentagram_image(int size, bool nonzero) {
  const Polygon star = pentagram();
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

}  // namespace
}  // namespace illum::lesson03

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson03", "Orientation and convex tests",
      "Pentagram under parity and nonzero rules, naive vs robust orientation, watertight "
      "ray–triangle on a mesh's edges, and the cost of parity, winding and convex tests.",
      TimedCores::one};  // every timing on one thread: the main job may run it beside another
  return run_program(argc, argv, info, {}, [&](const ProgramOptions& options) {
    const lesson03::Settings settings{.quick = options.quick, .seed = options.seed};
    OutputFolder out(options.out, info.id, info.title);
    Rng rng(options.seed);  // §2 and §5 draw from it in turn
    run_section(info.id, "§2 Floating point gets the sign wrong",
                [&] { lesson03::s02_orientation_signs(out, settings, rng); });
    run_section(info.id, "§3 Oriented crossings: the winding number", [&] {
      const int size = settings.quick ? 96 : 400;
      out.image(lesson03::pentagram_image(size, false), "pentagram_parity",
                "Pentagram, parity rule: the centre (winding 2) is a hole");
      out.image(lesson03::pentagram_image(size, true), "pentagram_nonzero",
                "Pentagram, nonzero rule: the centre (winding 2) is filled");
      const Polygon star = lesson03::pentagram();
      std::cout << "pentagram: winding number " << winding_number(star, Vec2(0.0, 0.0)) << " at the centre, "
                << winding_number(star, Vec2(0.0, 0.8)) << " in the top point, "
                << winding_number(star, Vec2(1.0, -1.0)) << " outside\n";
    });
    run_section(info.id, "§4 Convex polygons", [&] { lesson03::s04_containment_cost(out, settings); });
    run_section(info.id, "§5 Ray–triangle, watertight",
                [&] { lesson03::s05_watertight(out, settings, rng); });
    out.finish();
  });
}
