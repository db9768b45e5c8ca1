#pragma once
// A pixel's ray tree as the inspector shows it (lesson 06, §7; `illum trace`,
// `illum lab`). The record (ray_tree_record.hpp) holds one node per ray cast,
// in the order evaluate cast them; the view groups and explains those nodes
// without asking anything more of evaluate, so a student's evaluate that
// makes the recording calls of ray_tree.hpp gets all of it:
//
// * One shadow ray, however many surfaces it crosses. shadow_transmission
//   casts the ray again from each transmissive surface it crosses, and each
//   piece is recorded as a node of its own, a child of the same surface
//   aimed at the same light. The view joins the children of one node aimed
//   at one light into one shadow ray whose segments are those pieces.
// * What became of each possible child of a surface hit: cast, or why not —
//   the depth limit, total internal reflection, pruning by contribution
//   (lesson 07), a zero factor the plan skips, a kind the plan switches off.
//   Decided from the scene's materials, the plan, the depth and the path
//   weight exactly as evaluate's contract (ray_tree.hpp) decides them; a
//   child the contract asks for that the record lacks is reported as such
//   (a bug in evaluate, or a recording call left out).
// * Why each leaf is a leaf: it missed everything (the background), it hit
//   the depth limit, its children were pruned, its surface has neither k_r
//   nor k_t, or — for a shadow ray — it reached its light or was blocked.
//
// Numbers for people (display_number, display_colour) are rounded: three
// significant digits, and anything below 1e-6 in magnitude shown as 0 (a
// Phong highlight of (R·V)^n far from the mirror direction is 10^-60 and
// changes no 8-bit pixel). The JSON keeps the exact values.
#include <cstdint>
#include <string>
#include <vector>

#include "illum/trace/ray_tree_render.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

// What became of one possible child (reflected or refracted) of a surface hit.
enum class BranchFate {
  cast,                       // the child is in the tree
  depth_limit,                // the hit is at the depth limit: no children at all
  total_internal_reflection,  // refraction only: no transmitted ray, k_t went to the reflected one
  pruned,                     // its path weight fell below the pruning threshold (lesson 07)
  zero_factor,                // k_r (or k_t) is 0 here and the plan skips zero weights
  switched_off,               // the plan casts no ray of this kind in this scene
  not_cast,                   // evaluate's contract asks for it, but the record has none
};
const char* to_string(BranchFate fate);

// Why the tree stops at a node.
enum class StopReason {
  continues,      // it has a reflected or refracted child (shadow rays do not count)
  missed,         // the ray hit nothing: it returns the background
  depth_limit,    // the hit is at the depth limit
  pruned,         // every child it could have had was pruned (lesson 07)
  no_secondary,   // k_r = k_t = 0 at the hit (or the plan switches both kinds off)
  not_cast,       // a child the contract asks for is missing from the record
  reached_light,  // a shadow ray that reached its light (through glass or not)
  blocked,        // a shadow ray stopped by an opaque surface (or by glass that stops every channel)
};
const char* to_string(StopReason reason);

struct RayTreeBranch {
  RayKind kind = RayKind::reflection;
  BranchFate fate = BranchFate::cast;
  Color factor{0.0};  // the k that weighs the child (k_r with k_t added on total internal reflection)
  int child = -1;     // the view node of the child when it was cast
};

// One piece of a shadow ray: from `origin` to `end`, where it met a
// transmissive surface (`crossed`) or reached the light's end of its range.
struct ShadowSegment {
  Point3 origin{0.0}, end{0.0};
  bool crossed = false;  // ended on a surface (crossed it, or was stopped by it)
  std::uint32_t primitive = no_primitive, material = no_material;
  double t = 0;  // the parameter of `end` along the piece
  bool front_face =
      true;  // the surface's side met, as the hit record said (false: leaving glass from inside)
  Color transmission{1.0};  // the light's share that gets this far
};

struct RayTreeViewNode {
  RayKind kind = RayKind::primary;
  int depth = 0;
  int parent = -1;                      // view index
  std::vector<int> children;            // view indices, in the order they were cast
  std::vector<int> rays;                // the record's nodes it stands for (a shadow ray: one per segment)
  std::vector<RayTreeBranch> branches;  // surface hits of primary and secondary rays: reflection, refraction
  std::vector<ShadowSegment> segments;  // shadow rays
  StopReason stop = StopReason::continues;
};

// The view's nodes in the order of their first ray (node 0 is the primary
// ray when the tree is not empty).
struct RayTreeView {
  std::vector<RayTreeViewNode> nodes;
};

// Builds the view of `pixel` (traced in `scene`). Throws std::invalid_argument
// when the record is not a tree of this scene (a parent after its child, an
// index out of range).
RayTreeView view_ray_tree(const Scene& scene, const PixelTree& pixel);

// One sentence: why `node` stops, or what became of its branches; "" for
// a node that simply continues.
std::string stop_text(const Scene& scene, const PixelTree& pixel, const RayTreeView& view, int node);

// A number as people read it: three significant digits ("0.9", "9e-05"),
// 0 below 1e-6 in magnitude, "inf" and "nan" spelled out.
std::string display_number(double value);
// "0.9" when the three channels read the same, else "(0.675, 0.101, 0.0715)".
std::string display_colour(const Color& colour);

// The name of primitive `primitive`, "primitive N" when it has none, or `unknown`
// for no_primitive and an index past the scene's primitives.
std::string primitive_name(const Scene& scene, std::uint32_t primitive, const std::string& unknown);
// The name of material `material`, or "?" past the scene's materials.
std::string material_name(const Scene& scene, std::uint32_t material);
// The name of light `light` (points first, then areas), or "light N".
std::string light_name(const Scene& scene, std::uint32_t light);

}  // namespace illum
