#pragma once
// Lesson 14: the quadtree of elements on each input patch (Hanrahan, Salzman
// and Aupperle 1991). Every input patch is the root of a tree; an element is
// split into four children when the link oracle asks for it (a quad through
// its edge midpoints, a triangle through the midpoints of its sides), so
// the children tile their parent exactly (a parallelogram's or a triangle's
// four children have a quarter of its area each; a trapezoid's differ).
// Links join two elements of any levels: the receiver gathers radiosity from
// the source through the link's form factor. Lesson 14's exercise
// (hierarchical_radiosity.hpp) builds the links and solves on them; this file
// holds the data and the tree's plumbing.
#include <cstddef>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

struct HierarchyElement {
  Patch patch;           // its polygon, normal, centroid, area, ρ, E and surface (those of its root)
  int parent = -1;       // −1 for a root (an input patch)
  int first_child = -1;  // children first_child … first_child + 3; −1 for a leaf
  int level = 0;         // 0 for a root, parent's level + 1 below it
  Color radiosity{0.0};  // B: at a leaf E + everything gathered on it and its ancestors;
                         // above the leaves, the area-weighted mean of its children
  Color gathered{0.0};   // B_g: what its own links bring, ρ Σ F B_source
};

// A link: `receiver` gathers from `source` through form_factor, the form
// factor from the receiver to the source with visibility included
// (link_form_factor): the link brings ρ_receiver · form_factor · B_source.
struct Link {
  int receiver = -1;
  int source = -1;
  double form_factor = 0;
};

struct ElementHierarchy {
  std::vector<HierarchyElement> elements;  // elements[0, roots) are the input patches, in their order
  std::size_t roots = 0;
  std::vector<Link> links;

  HierarchyElement& operator[](int e) { return elements[static_cast<std::size_t>(e)]; }
  const HierarchyElement& operator[](int e) const { return elements[static_cast<std::size_t>(e)]; }
  bool is_leaf(int e) const { return (*this)[e].first_child < 0; }
};

// One root per input patch, with B = E (every patch a leaf, no links).
// Throws std::invalid_argument when a patch has not 3 or 4 vertices.
ElementHierarchy make_hierarchy(const std::vector<Patch>& patches);

// The four children of `element`, created (B = the parent's B, B_g = 0,
// appended to h.elements) the first time; returns the index of the first.
// Appending may move the elements: hold indices, not references, across it.
// Throws std::invalid_argument for an element out of range.
int subdivide(ElementHierarchy& h, int element);

// The points where the visibility of a link is sampled on `patch`: the
// centroids of its k × k split (a quad's bilinear cells, a triangle's k²
// similar triangles), k = points_per_side ≥ 1; k = 1 is the centroid.
// Throws std::invalid_argument unless 1 ≤ points_per_side ≤ 8.
std::vector<Point3> sample_points(const Patch& patch, int points_per_side);

// True when no light can pass between the two: every vertex of `b` lies on
// or behind the plane of `a`, or every vertex of `a` on or behind the plane of
// `b` (within 1e-9 of the vertex's distance from the other's centroid, so a
// coplanar pair faces away however its coordinates round). Two elements that
// share an edge at an angle below 180° face each other.
bool faces_away(const Patch& a, const Patch& b);

// The leaves of the hierarchy, in order of their index.
std::vector<int> leaves(const ElementHierarchy& h);

// How far `point` (a point of the patch's plane) lies inside the convex
// patch: the smallest of its distances to the lines of the edges, measured
// in the plane, negative outside the nearest edge.
double depth_inside(const Patch& patch, const Point3& point);

// The leaf below `root` that holds `point` (a point of the root's plane):
// from the root down, the child the point is deepest inside of (the largest
// of its signed distances to the child's edges, least negative outside), so
// a point on a shared edge finds one of the two and rounding never loses it.
int leaf_at(const ElementHierarchy& h, int root, const Point3& point);

}  // namespace illum
