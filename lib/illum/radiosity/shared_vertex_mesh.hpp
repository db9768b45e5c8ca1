#pragma once
// Lesson 12: which patches share which vertices. A radiosity mesh stores
// every patch with its own copy of its corners; to give a vertex one colour
// the patches that meet there must be found, and only patches of the same
// surface and orientation may share it: the floor and the back wall meet
// along an edge, but their radiosities are unrelated, and averaging across
// that edge would blur the crease that the picture must keep.
//
// Invariants of a SharedVertexMesh built by share_vertices:
//   - faces[f] lists face f's corners counter-clockwise (the order of
//     patches[f].vertices), as indices into `positions`;
//   - two faces list the same vertex only when they are in the same smooth
//     group: same orientation (normals within max_normal_angle_degrees) and
//     connected through shared corners. A point where two walls meet is two
//     vertices, one per wall;
//   - a T-vertex is a vertex that lies strictly inside an edge of a face of
//     its group that does not list it (a large patch beside two halves of
//     a split one); t_vertices names it with that edge, in the order in
//     which they can be resolved (an edge's own ends come first);
//   - on_boundary[v] is true when v is an end of an edge piece that no
//     other face of the group covers: the edge of a wall, not an inside edge;
//   - neighbours lists each pair of faces (f < g) that share a piece of an
//     edge, T-vertices included, once.
#include <utility>
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"

namespace illum {

// A vertex inside an edge (from → to) of `face` that the face does not list:
// positions[vertex] = (1 − t)·positions[from] + t·positions[to], 0 < t < 1.
struct TVertex {
  int vertex = -1;
  int face = -1;
  int from = -1, to = -1;
  double t = 0;
};

struct SharedVertexMesh {
  std::vector<Point3> positions;
  std::vector<std::vector<int>> faces;
  std::vector<int> group;  // per face: its smooth group
  std::vector<bool> on_boundary;
  std::vector<TVertex> t_vertices;
  std::vector<std::pair<int, int>> neighbours;
};

struct VertexSharing {
  double max_normal_angle_degrees = 1.0;  // faces within this angle may share vertices
  double relative_tolerance = 1e-9;       // points closer than this × scene size are one point
};

// Builds the shared-vertex mesh of `patches` (face f = patches[f]). Throws
// std::invalid_argument when there are no patches or a setting is not
// positive and finite.
SharedVertexMesh share_vertices(const std::vector<Patch>& patches, const VertexSharing& sharing = {});

// Every face's corners with its T-vertices inserted in order along each
// edge: the polygons to hand to a renderer that interpolates colours along
// edges (OpenGL, MeshLab), so that the large face's edge passes through the
// T-vertex's colour and the picture has no crack.
std::vector<std::vector<int>> display_polygons(const SharedVertexMesh& mesh);

// The parameters (u, v) of `point` on a patch: for a quadrilateral p0 p1 p2 p3
// the inverse of the bilinear map
//   x(u, v) = (1 − u)(1 − v) p0 + u(1 − v) p1 + u v p2 + (1 − u) v p3,
// for a triangle p0 p1 p2 the barycentric (u, v) of x = p0 + u(p1 − p0) + v(p2 − p0).
// The point is projected onto the patch's plane first. Throws
// std::invalid_argument for a patch with another number of vertices.
std::pair<double, double> patch_parameters(const Patch& patch, const Point3& point);

}  // namespace illum
