// §8 The study: its system.
//
// The Cornell box meshed coarsely (75 mm patches), its form factors by the
// hemicube (lesson 10) at resolution 96, made reciprocal by averaging
// A_i F_ij with A_j F_ji (reciprocal_average): one system every solver solves.
#include <algorithm>
#include <iostream>
#include <string>

#include "illum/core/stopwatch.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson11 {

StudySystem s08a_form_factors(OutputFolder& out, const Settings& settings) {
  StudySystem s;
  s.edge = settings.quick ? 220.0 : 75.0;
  s.resolution = settings.quick ? 32 : 96;
  s.scene = load_radiosity_scene(settings.scene, s.edge);
  report_progress(program_id,
                  "hemicube form factors for " + std::to_string(s.scene.patches.size()) + " patches", 0, 1);
  Stopwatch watch;
  const FormFactorMatrix hemicube_f = hemicube_form_factors(s.scene.patches, s.resolution);
  const double seconds = watch.seconds();
  s.f = reciprocal_average(hemicube_f, s.scene.patches);
  check_form_factors(s.f, 1e-12);
  double largest_row = 0;
  for (std::size_t i = 0; i < s.f.size(); ++i) largest_row = std::max(largest_row, s.f.row_sum(i));
  Table t({"patches", "hemicube resolution", "seconds", "reciprocity error before averaging", "after",
           "largest row sum"});
  t.add_row({static_cast<std::int64_t>(s.f.size()), static_cast<std::int64_t>(s.resolution), seconds,
             reciprocity_error(hemicube_f, s.scene.patches), reciprocity_error(s.f, s.scene.patches),
             largest_row});
  out.table(t, "study_form_factors", "The study's form factors: hemicube, then made reciprocal by averaging");
  std::cout << "Study: " << s.scene.patches.size() << " patches, hemicube " << s.resolution
            << " form factors in " << fixed(seconds, 2) << " s\n";
  return s;
}

}  // namespace illum::lesson11
