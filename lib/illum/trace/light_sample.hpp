#pragma once
// The lights as the ray tree sees them: one point per light.
#include <cstddef>

#include "illum/trace/scene.hpp"

namespace illum {

// Where a light is for the ray tree: its position and intensity I_l. An area
// light is one point at its polygon's centroid, with its emission as I_l
// (one shadow ray per light, as the notes' algorithm has it; lesson 07
// samples an area light properly). Lights are numbered points first, then areas.
struct LightSample {
  Point3 position{0.0};
  Color intensity{0.0};
};
std::size_t light_count(const Scene& scene);
LightSample light_sample(const Scene& scene, std::size_t light);

}  // namespace illum
