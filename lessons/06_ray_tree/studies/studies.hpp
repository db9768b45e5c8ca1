#pragma once
// Lesson 06's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: Whitted's scene by
// the ray tree) calls them in the text's order.
#include <array>
#include <cstdint>
#include <optional>

#include "illum/io/output_folder.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "illum/trace/scene.hpp"

namespace illum::lesson06 {

// What the command line sets.
struct Settings {
  bool quick = false;                       // --quick: small sizes
  std::uint64_t seed = 1;                   // --seed
  std::optional<std::array<int, 2>> pixel;  // --pixel X Y: the pixel the inspector records
  std::uint64_t forward_photons = 1000000;  // --forward-rays: the most photons of §2's study
};

// The depth limit of the demonstration and of most studies.
constexpr int default_depth = 5;

// How Whitted's scene is rendered: the scene camera's size (96 × 72 with
// --quick), a sky-blue background.
inline RenderSettings whitted_settings(bool quick, int depth = default_depth) {
  return {.width = quick ? 96 : 0,
          .height = quick ? 72 : 0,
          .max_depth = depth,
          .background = Color(0.35, 0.55, 0.9)};
}

// §1: the transport equation marched along a ray through a slab, against
// Beer–Lambert's closed form (studies/s01_radiation_slab.cpp).
void s01_radiation_slab(OutputFolder& out, const Settings& settings);

// §2: forward tracing from the light, the pixels its photons reach against
// the backward tracer's one ray per pixel (studies/s02_forward_tracing.cpp).
void s02_forward_tracing(OutputFolder& out, const Scene& whitted, const Settings& settings);

// §4: how often a secondary ray leaving a sphere meets it again, by how it
// leaves (studies/s04_offset_study.cpp).
void s04_offset_study(OutputFolder& out, const Settings& settings);

// §6: every shipped scene with and without the effects plan, its ray counts
// (studies/s06_effects_plan.cpp).
void s06_effects_plan(OutputFolder& out, const Settings& settings);

// §7: one pixel's whole ray tree as JSON, Graphviz and an overlay on the
// demonstration's image (studies/s07_inspector.cpp).
void s07_inspector(OutputFolder& out, const Scene& whitted, const RenderResult& render,
                   const Settings& settings);

// §8: image error, rays and time against the depth limit
// (studies/s08_depth_study.cpp).
void s08_depth_study(OutputFolder& out, const Scene& whitted, const Settings& settings);

// §8: the share of the render's time spent in intersection tests
// (studies/s08_intersection_share.cpp).
void s08_intersection_share(OutputFolder& out, const Scene& whitted, const Settings& settings);

}  // namespace illum::lesson06
