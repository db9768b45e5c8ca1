#pragma once
// The ray-tree inspector's three views of one pixel's tree (lesson 06, §7):
// JSON (every node with its numbers), a Graphviz drawing of the tree, and
// the rays' paths drawn over the rendered image.
#include <optional>
#include <string>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/trace/ray_tree_render.hpp"
#include "illum/trace/scene.hpp"

namespace illum {

// {"scene", "pixel": [x, y], "color", "nodes": n, "tree": {kind, origin,
// direction, hit: {primitive, t, point, material, front_face} | null,
// local, weight, color, children: [...]}} — the tree nested as it grew.
std::string ray_tree_json(const Scene& scene, const PixelTree& pixel);

// A Graphviz digraph: one box per ray (kind, what it hit and where, I_own,
// weight), edges labelled with the factor that weighs the child (k_r, k_t,
// or "shadow"), shadow rays dashed and red when blocked.
std::string ray_tree_dot(const Scene& scene, const PixelTree& pixel);

// Where a point appears in the image of `camera` (pixel coordinates, x to
// the right, y down), or nothing when it lies behind the eye.
std::optional<Vec2> project_to_image(const PinholeCamera& camera, const Point3& point);

// `render` with the tree's rays drawn on it (primary white, reflection cyan,
// refraction orange, shadow yellow, blocked shadow red) and the pixel ringed.
// `camera` is the one that made `render`.
Image ray_tree_overlay(const Image& render, const PinholeCamera& camera, const PixelTree& pixel);

}  // namespace illum
