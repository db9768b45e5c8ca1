#pragma once
// The lights as the ray tree sees them: one point per light, and the
// intensity I_l of the notes' model that it sends to a given point.
#include <cstddef>

#include "illum/trace/scene.hpp"

namespace illum {

struct LightSample {
  Point3 position{0.0};
  Color intensity{0.0};  // I_l in I_own's sum, for the point the sample was taken for
};

// Lights are numbered point lights first, then area lights.
std::size_t light_count(const Scene& scene);

// Light `light` as seen from `at`.
// * A point light is its position and intensity, without distance falloff:
//   the notes' local model and Whitted's (1980) treat I_l as a constant.
// * An area light is one point, its polygon's centroid (one shadow ray per
//   light, as "evaluar (rayo)" has it; lesson 07 samples the polygon), with
//   I_l = E·A·cos θ_l/(π r²): its emission E times the small-polygon form
//   factor from the point to the light (lesson 09), zero behind the side
//   that emits (counter-clockwise seen from it).
LightSample light_sample(const Scene& scene, std::size_t light, const Point3& at);

}  // namespace illum
