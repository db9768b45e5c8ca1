// Lesson 12's one way to solve a box: patches shoot, elements receive
// (radiosity/substructuring.hpp), shared by the demonstration and the studies.
#include "illum/io/scene_file.hpp"
#include "studies/studies.hpp"

namespace illum::lesson12 {

ShootingSettings with_occluders(ShootingSettings shooting, const RadiosityScene& scene) {
  for (const RadiositySurface& surface : scene.surfaces) shooting.occluders.push_back(surface.polygon);
  return shooting;
}

Solved solve(const Settings& settings, double patch_edge, int k, const ShootingSettings& shooting) {
  Solved s;
  s.scene = load_radiosity_scene(settings.scene, patch_edge);
  s.mesh = uniform_elements(s.scene.patches, k);
  s.solution = shoot_patches_to_elements(s.scene.patches, s.mesh, with_occluders(shooting, s.scene));
  s.shared = share_vertices(s.mesh.elements);
  return s;
}

}  // namespace illum::lesson12
