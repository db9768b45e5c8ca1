#pragma once
// The ray-tree inspector's three views of one pixel's tree (lesson 06, §7):
// JSON (every node with its numbers), a Graphviz drawing of the tree, and
// the rays' paths drawn over the rendered image. All three show the tree as
// ray_tree_view.hpp groups and explains it: a shadow ray that crosses glass
// is one node with its segments, and every leaf says why it stops.
#include <optional>
#include <string>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

// {"scene", "pixel": [x, y], "color", "nodes": the view's nodes, "rays": the
// rays cast (a shadow ray counts once per segment), "depth_limit",
// "depth_requested", "min_contribution", "rays_by_kind", "tree": {id, kind,
// depth, rays: [record indices], origin, direction, hit: {primitive,
// primitive_index, t, point, material, front_face} | null, local, weight,
// color, stop: {reason, text}, branches: [{kind, fate, factor}] (surface
// hits), light, light_name, light_end, transmission, segments: [{origin,
// end, hit | null, transmission}] (shadow rays), total_internal_reflection
// (when it happened), children: [...]}} — the tree nested as it grew.
// Exact numbers (doubles); `illum lab`'s GET /api/trace returns this text.
std::string ray_tree_json(const Scene& scene, const PixelTree& pixel);

// A Graphviz digraph: one box per node of the view (kind, what it hit and
// where, I_own, weight, why it stops; a shadow ray lists the surfaces it
// crossed), edges labelled with the factor that weighs the child (k_r, k_t,
// or "shadow"), shadow rays dashed and red when blocked, and a dotted stub
// for a child that total internal reflection, pruning or a missing call took
// away. Numbers rounded by display_colour.
//
// `TreeDetail::summary` keeps three lines per box (the kind and depth, what
// it hit or why it ended, the weight) in a larger font: a drawing that stays
// readable on a slide, where the full one's boxes shrink to a few pixels.
enum class TreeDetail { full, summary };
std::string ray_tree_dot(const Scene& scene, const PixelTree& pixel, TreeDetail detail = TreeDetail::full);

// Where a point appears in the image of `camera` (pixel coordinates, x to
// the right, y down), or nothing when it lies behind the eye.
std::optional<Vec2> project_to_image(const PinholeCamera& camera, const Point3& point);

// `render` with the tree's rays drawn on it (primary white, reflection cyan,
// refraction orange, shadow yellow, the blocked segment of a shadow ray red),
// the pixel ringed, and a legend in a strip added below the image (the
// overlay is taller than `render` by that strip). A ray that runs
// almost along the line of sight projects to a few pixels: it is drawn as a
// circle with a dot (towards the camera) or a cross (away from it), the
// usual notation for an arrow seen end-on. `camera` is the one that made
// `render`.
Image ray_tree_overlay(const Image& render, const PinholeCamera& camera, const PixelTree& pixel);

}  // namespace illum
