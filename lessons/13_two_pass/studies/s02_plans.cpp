// §2 The plan grows to the whole pipeline: the plans of five shipped scenes.
//
// For each scene of scenes/, the two-pass plan (radiosity/two_pass_plan.hpp,
// the exercise): whether a caustic pass and a radiosity pass run, which rays
// the eye pass casts; and the patches, shots and rays each pass then took
// (pass one at 100 mm patches and 1% unshot, pass two 48 pixels wide).
#include <string>

#include "illum/io/scene_file.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson13 {

void s02_plans(OutputFolder& out, const Settings& s) {
  Table t({"scene", "caustic pass", "radiosity pass", "reflected rays", "refracted rays", "shadow rays",
           "depth limit", "receiver patches", "occluder patches", "shots", "primary rays", "reflection rays",
           "refraction rays", "shadow rays cast"});
  Settings small = s;
  small.edge = 100, small.unshot = 1e-2, small.hemicube = 32;
  for (const std::string name : {"cornell_spheres", "cornell", "whitted", "spheres", "primitives"}) {
    const Scene scene = load_scene(name);
    const PipelineRun r = run_pipeline(scene, name, small, false, 48);
    const RayCounts& rays = r.eye.stats.rays;
    t.add_row({name, yes_no(r.plan.caustic_pass), yes_no(r.plan.radiosity_pass), yes_no(r.plan.reflection),
               yes_no(r.plan.refraction), yes_no(r.plan.shadow_rays), std::int64_t{r.plan.max_depth},
               count(r.mesh.receiver_patches), count(r.mesh.occluder_patches),
               count(r.radiosity.hemicube_rows), count(rays.primary), count(rays.reflection),
               count(rays.refraction), count(rays.shadow)});
  }
  out.table(t, "plans",
            "The plans of five shipped scenes and the counts of each pass (pass one at 100 mm patches, 1% "
            "unshot; pass two 48 pixels wide)");
}

}  // namespace illum::lesson13
