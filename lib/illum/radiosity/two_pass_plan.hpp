#pragma once
// Exercise unit of lesson 13: students write two_pass_plan.cpp.
// The effects plan of the whole pipeline (lesson 13, §2): which passes of
// two-pass global illumination a scene calls for. Lesson 06's plan decides
// the rays of one ray tree; this one decides, before any work, whether the
// radiosity pass (pass one) runs, whether the caustic pass runs before it,
// and which rays the eye pass (pass two) casts.
//
// The plan reads a SceneInventory, the counts it needs (two_pass.hpp's
// scene_inventory fills one from a Scene), so that it can be checked on
// inventories written by hand.
#include <cstddef>
#include <string>

namespace illum {

// What the plan needs to know about a scene.
struct SceneInventory {
  // Polygons and triangles with k_d > 0 in some channel and no k_r, k_t:
  // the surfaces pass one meshes into patches and that reflect light.
  std::size_t diffuse_surfaces = 0;
  // Unordered pairs of those surfaces that face each other (each has a
  // vertex strictly in front of the other's plane): the pairs between which
  // light can bounce from one diffuse surface to another (occlusion ignored).
  std::size_t facing_pairs = 0;
  std::size_t emitters = 0;      // emitting polygons and triangles (area lights)
  std::size_t point_lights = 0;  // point lights: they never feed pass one (it meshes surfaces only)
  std::size_t mirrors = 0;       // primitives whose material has k_r > 0 and k_t = 0
  std::size_t glass = 0;         // primitives whose material has k_t > 0
  // Diffuse primitives that are not meshed (spheres, meshes, …): pass two lights them with shadow rays.
  std::size_t other_diffuse = 0;
  double heaviest_specular = 0;  // the largest k_r + k_t of any material in any channel
};

// What the program asks for.
struct TwoPassRequest {
  int max_depth = 5;      // the deepest specular ray of pass two (≥ 0)
  bool caustics = false;  // deposit light reflected or refracted by specular surfaces before the solve
};

struct TwoPassPlan {
  bool caustic_pass = false;  // light rays from the emitters through specular surfaces, deposited on patches
  bool radiosity_pass = false;  // pass one: mesh the diffuse surfaces and solve for B
  bool reflection = false;      // pass two spawns reflected rays
  bool refraction = false;      // pass two spawns refracted rays
  bool shadow_rays = false;     // pass two lights some diffuse surface directly (light not in B)
  int max_depth = 0;            // the depth limit of pass two's specular rays (0: primary rays only)
  // One line per decision, saying why; the word "caustic" appears only when caustics were asked
  // for, the words "no emitter" exactly when pass one does not run for want of an emitter, and
  // "no shadow rays" exactly when shadow_rays is false (its line then says why none are needed).
  std::string reasons;

  // The decisions and their reasons, one per line (defined in two_pass.cpp).
  std::string summary() const;
};

// Task 1. The plan (lesson 13, §2), decision by decision:
// * pass one runs when light can bounce between diffuse surfaces: an
//   emitter and at least one facing pair. A wall and a light have no pair:
//   pass two lights the wall directly, there is nothing to solve.
// * the caustic pass runs when it is requested and the scene has an
//   emitter, a mirror or glass, and a diffuse surface pass one meshes
//   (diffuse_surfaces > 0; a diffuse sphere, other_diffuse, has no patches
//   to receive); it forces pass one, whose patches carry the deposits and
//   spread them further.
// * reflected rays when there is a mirror or glass (glass reflects totally
//   inside); refracted rays when there is glass; none of either → depth 0.
// * the depth limit is the request (kept when it is smaller), cut as lesson
//   06's plan cuts it (trace/effects_plan.hpp): to the first depth d ≥ 1
//   with std::pow(heaviest_specular, d) ≤ contribution_threshold, at or
//   below it (0.3 → 6, as 0.3^5 > 1/1024 ≥ 0.3^6; 0.5 → 10, as 0.5^10 =
//   1/1024 exactly). ⌈ln(1/1024)/ln k⌉ alone can be one off where k^d lies
//   within rounding of 1/1024 (k one ulp above 2⁻¹⁰ gives 1, yet k^1 >
//   2⁻¹⁰: d = 2): check the depth it gives against k^d. No cut when
//   heaviest_specular is 1: lossless glass never falls to the threshold;
//   nor, in practice, when it is a hair below 1 (1 − 1e-12 needs about
//   7·10¹² levels, far more than an int holds: count in double).
// * shadow rays when a light reaches a diffuse surface whose direct light B
//   does not hold: any point light with a diffuse surface (meshed or not);
//   an emitter with other_diffuse > 0, or with diffuse_surfaces > 0 when
//   pass one does not run.
// Throws std::invalid_argument when request.max_depth < 0 (its message
// contains "depth") or when heaviest_specular > 1 (no tolerance: exactly 1 is
// lossless glass and allowed) or is not a number (its
// message contains "k_r + k_t"; k_r + k_t > 1 creates energy: a ray tree that
// reflects more than it receives diverges with depth).
TwoPassPlan plan_two_pass(const SceneInventory& scene, const TwoPassRequest& request);

}  // namespace illum
