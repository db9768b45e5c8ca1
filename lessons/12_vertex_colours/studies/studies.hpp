#pragma once
// Lesson 12's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: the box solved by
// substructuring and drawn with the three vertex-colour rules) calls them in
// the text's order.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "illum/io/output_folder.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/shared_vertex_mesh.hpp"
#include "illum/radiosity/substructuring.hpp"
#include "illum/radiosity/vertex_colours.hpp"

namespace illum::lesson12 {

inline constexpr const char* program_id = "lesson12";

// What the command line sets (validated there, before anything is written).
struct Settings {
  std::string scene = "cornell";
  bool quick = false;
  double threshold = 0.05;        // subdivision: a gap above this fraction of the brightest element splits
  std::filesystem::path ply;      // --ply: also write the figure's binary PLY here
  int figure_elements = 10000;    // the figure's element count (about)
  double figure_patch_edge = 75;  // mm: the figure's patches (the shooters)
  double unshot = 1e-3;           // stop at this fraction of the emitted power unshot
  bool figure_only = false;       // --figure: only the figure (section 7) and its export (section 8)
  int threads = 0;  // --threads as given (0: not given); N ≥ 2 adds the figure's runs on N threads
};

// The three vertex-colour rules of §1–3 and their names, in the order the pictures show them.
inline const std::vector<std::pair<VertexColourRule, std::string>> rules = {
    {VertexColourRule::patch_own, "patch_own"},
    {VertexColourRule::average, "average"},
    {VertexColourRule::extrapolate, "extrapolate"}};

// A solved element mesh: the scene, its elements, their radiosity and who shares which vertex.
struct Solved {
  RadiosityScene scene;
  ElementMesh mesh;
  SubstructuredSolution solution;
  SharedVertexMesh shared;
};

// `shooting` with the scene's surfaces as the occluders of the ray-cast rows
// (a few dozen triangles in the BVH instead of two per patch).
ShootingSettings with_occluders(ShootingSettings shooting, const RadiosityScene& scene);

// The scene --scene names, meshed into patches of at most `patch_edge` mm,
// each split k × k into elements, solved by shooting from the patches to the
// elements (radiosity/substructuring.hpp) with the scene's surfaces as the
// occluders of the ray-cast rows; and who shares which vertex.
Solved solve(const Settings& settings, double patch_edge, int k, const ShootingSettings& shooting);

// §6: uniform against adaptive substructuring, error against a uniformly fine
// solution and time, per element count (studies/s06_substructuring.cpp).
void s06_substructuring(OutputFolder& out, const Settings& settings);

// §7: the box at about 10,000 elements, both visibility methods on one thread
// (and on --threads N as well when N ≥ 2 is asked for); returns the ray-cast
// solution of one thread (studies/s07_figure.cpp).
Solved s07_figure(OutputFolder& out, const Settings& settings);

// §8: the figure's solution as PLY and OBJ with vertex colours (studies/s08_export.cpp).
void s08_export(OutputFolder& out, const Settings& settings, const Solved& figure);

}  // namespace illum::lesson12
