// §4 What classic two-pass misses: caustics.
//
// The pipeline again with a caustic pass: light rays from the emitter
// through the spheres deposit their light on the patches they reach after a
// specular bounce, before pass one (radiosity/two_pass.hpp); the picture
// without it, with it, and the light it added.
#include <iostream>

#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson13 {

PipelineRun s04_caustics(OutputFolder& out, const Scene& scene, const Settings& s, const Image& classic) {
  PipelineRun with = run_pipeline(scene, s.scene, s, true, s.width);
  const double exposure = exposure_for(classic);
  Image gain(classic.width(), classic.height());
  for (int y = 0; y < gain.height(); ++y)
    for (int x = 0; x < gain.width(); ++x)
      gain.at(x, y) = 4.0 * exposure * max(with.eye.image.at(x, y) - classic.at(x, y), Color(0.0));
  out.image(side_by_side({exposed(classic, exposure), exposed(with.eye.image, exposure), gain}, Color(0.5)),
            "caustics", "Classic two-pass, with the caustic pass, and the light it added (×4)");
  Table t({"photons", "first hit specular", "deposited on patches", "caustic pass seconds",
           "pass one seconds", "shots"});
  t.add_row({count(with.caustics.photons), count(with.caustics.specular_first),
             count(with.caustics.deposited), with.caustics.seconds, with.radiosity.seconds,
             count(with.radiosity.hemicube_rows)});
  out.table(t, "caustic_pass", "The caustic pass: light rays from the emitter through the spheres");
  std::cout << "caustic pass: " << with.caustics.photons << " light rays, " << with.caustics.deposited
            << " deposited after a specular bounce\n";
  return with;
}

}  // namespace illum::lesson13
