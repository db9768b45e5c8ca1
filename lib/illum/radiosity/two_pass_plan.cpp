// The plan of two-pass global illumination (lesson 13, §2). Exercise unit of lesson 13.
#include "illum/radiosity/two_pass_plan.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "illum/core/error.hpp"
#include "illum/trace/effects_plan.hpp"

namespace illum {

TwoPassPlan plan_two_pass(const SceneInventory& scene, const TwoPassRequest& request) {
  require(request.max_depth >= 0, "plan_two_pass: the depth limit must not be negative");
  require(scene.heaviest_specular <= 1.0,
          "plan_two_pass: k_r + k_t > 1 in a material: a surface would reflect more light than it receives");
  TwoPassPlan plan;
  std::string& why = plan.reasons;
  const bool specular = scene.mirrors + scene.glass > 0;
  const bool receivers = scene.diffuse_surfaces > 0;

  plan.caustic_pass = request.caustics && scene.emitters > 0 && specular && receivers;
  if (request.caustics && !plan.caustic_pass) {  // names only what is missing ("no emitter" is pass one's)
    std::string missing;
    for (const auto& [absent, what] :
         {std::pair{scene.emitters == 0, "an emitter"}, std::pair{!specular, "a mirror or glass"},
          std::pair{!receivers, "a diffuse surface"}})
      if (absent) missing += (missing.empty() ? " " : ", ") + std::string(what);
    why += "  caustics asked for, but the scene lacks" + missing + ": no caustic pass\n";
  }
  if (plan.caustic_pass)
    why += "  caustic pass: light rays from the emitters through the specular surfaces\n";

  const bool interreflection = scene.emitters > 0 && scene.facing_pairs > 0;
  plan.radiosity_pass = interreflection || plan.caustic_pass;
  if (interreflection)
    why += "  an emitter and " + std::to_string(scene.facing_pairs) +
           " facing pair(s) of diffuse surfaces: light bounces, pass one solves for B\n";
  else if (plan.caustic_pass)
    why += "  no diffuse surfaces face each other, but the caustic deposits need patches: pass one runs\n";
  else
    why += scene.emitters == 0
               ? "  no emitter: nothing for pass one to distribute, no radiosity pass\n"
               : "  no two diffuse surfaces face each other: no interreflection, no radiosity pass\n";

  plan.reflection = specular;
  plan.refraction = scene.glass > 0;
  if (!specular) {
    why += "  no mirror and no glass: no specular rays, depth limit 0\n";
  } else {
    plan.max_depth = request.max_depth;
    if (scene.heaviest_specular < 1.0 && scene.heaviest_specular > 0.0) {
      // Compared in double: a weight a hair below 1 needs more levels than an int holds.
      const double w = scene.heaviest_specular;
      double useful = std::ceil(std::log(contribution_threshold) / std::log(w));
      // The ceiling of a rounded quotient can be one off where w^d lies within rounding of the threshold.
      while (useful > 1 && std::pow(w, useful - 1) <= contribution_threshold) --useful;
      while (std::pow(w, useful) > contribution_threshold) ++useful;
      if (useful < plan.max_depth) plan.max_depth = std::max(static_cast<int>(useful), 1);
    }
    why += std::string(plan.refraction ? "  glass: reflected and refracted rays"
                                       : "  mirrors only: reflected rays, no refracted ones") +
           ", depth limit " + std::to_string(plan.max_depth) + "\n";
  }

  const bool diffuse = receivers || scene.other_diffuse > 0;
  const bool point_direct = scene.point_lights > 0 && diffuse;
  const bool area_direct =
      scene.emitters > 0 && (scene.other_diffuse > 0 || (receivers && !plan.radiosity_pass));
  plan.shadow_rays = point_direct || area_direct;
  if (point_direct) why += "  point lights are not in B: shadow rays to them\n";
  if (area_direct) why += "  some diffuse surface is not in B: shadow rays to the emitters\n";
  if (!plan.shadow_rays)
    why += "  every diffuse surface's light is in B (or nothing is lit): no shadow rays\n";
  return plan;
}

}  // namespace illum
