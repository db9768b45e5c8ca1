// §8 Study: coincident-face artefacts against the tolerance.
//
// A blind hole and a square pocket whose openings lie in the box's top face:
// with no sliver tolerance the removed face survives as slivers one ulp long
// and shows through; too large a tolerance erases a genuinely thin solid (a
// coin 10⁻⁴ thick). Pixels of each, against the tolerance, and the two
// pictures of the blind hole.
#include <cmath>
#include <utility>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "solids.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson04 {
namespace {

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

}  // namespace

void s08_coincident_faces(OutputFolder& out, const Settings& settings) {
  const int width = settings.quick ? 120 : 400, height = settings.quick ? 90 : 300;
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

}  // namespace illum::lesson04
