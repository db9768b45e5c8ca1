#pragma once
// Lesson 14's pictures: the scene through its camera, one ray per pixel
// against its surfaces (brute force), each pixel the flat radiosity of the
// hierarchy's leaf it sees; the edges between elements drawn dark; the links
// of one element drawn as lines between the centroids. Not an exercise: the
// lesson is about the links, not about drawing them.
#include <vector>

#include "hierarchy_runs.hpp"
#include "illum/core/image.hpp"

namespace illum::lesson14 {

// The leaf each pixel sees (−1: none), and the camera that saw it.
struct LeafView {
  RadiosityCamera camera;
  int width = 0, height = 0;
  std::vector<int> leaf;
};
LeafView view_leaves(const HierarchicalSolution& s, const Roots& roots, int width, int height);

// An exposure that maps the 95th percentile of the non-emitting leaves'
// brightest channel to 0.85 (the lights saturate to white).
double exposure_for(const HierarchicalSolution& s);

// Each pixel exposure · B of its leaf; with `edges`, a pixel whose right or
// lower neighbour sees another element is drawn dark grey.
Image leaf_image(const LeafView& view, const HierarchicalSolution& s, double exposure, bool edges);

// Draws the links of `element` and of its ancestors over the picture: a line
// from the receiver's centroid to each source's centroid, yellow for the
// element's own links and blue for its ancestors' (they reach it by push-pull);
// each source outlined in the line's colour. Returns the number of links drawn.
int draw_links(Image& image, const LeafView& view, const HierarchicalSolution& s, int element);

// The non-emitting leaf with the largest radiosity (its brightest channel).
int brightest_leaf(const HierarchicalSolution& s);

}  // namespace illum::lesson14
