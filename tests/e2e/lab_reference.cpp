// The browser test's independent source for the lab's radiosity view: the
// library's own progressive solver (radiosity/progressive_on_demand.hpp, the
// run behind lesson 11's figure: rows on demand on every thread), on the
// Cornell box meshed as lesson 11's figure meshes it (patch edge 240 mm
// shrunk by 3% until there are at least N patches, the loop of lesson 11's
// scene_with_patches). Prints JSON: the patch count, the edge and the
// unshot fraction after each of the first SHOTS shots.
//
//   lab_reference SCENE MIN_PATCHES RESOLUTION SHOTS
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "illum/io/scene_file.hpp"
#include "illum/radiosity/production/progressive_on_demand.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: lab_reference SCENE MIN_PATCHES RESOLUTION SHOTS\n";
    return 2;
  }
  const std::string scene = argv[1];
  const std::size_t wanted = std::stoul(argv[2]), shots = std::stoul(argv[4]);
  const int resolution = std::stoi(argv[3]);
  double edge = 240.0;
  illum::RadiosityScene s = illum::load_radiosity_scene(scene, edge);
  for (int shrink = 0; s.patches.size() < wanted; ++shrink) {
    if (shrink == 1000) return 1;
    s = illum::load_radiosity_scene(scene, edge *= 0.97);
  }
  std::vector<double> fractions;
  const illum::Hemicube hemicube(resolution);
  // Run on until a third of the power is left (far past SHOTS on the box), recording every shot.
  illum::progressive_on_demand(
      s.patches, hemicube, {.unshot_fraction = 0.3},
      [&](const illum::ProgressiveState&, double unshot) { fractions.push_back(unshot); });
  if (fractions.size() < shots) {
    std::cerr << "lab_reference: only " << fractions.size()
              << " shots before a third of the power was left\n";
    return 1;
  }
  fractions.resize(shots);
  std::cout << nlohmann::json{{"patches", s.patches.size()}, {"edge", edge}, {"fractions", fractions}}.dump()
            << "\n";
  return 0;
}
