#pragma once
// Exercise unit of lesson 12: students write vertex_colours.cpp.
// Lesson 12 (exercise unit: vertex_colours.cpp): vertex colours, the notes'
// "Asignación de color por vértice". The radiosity solution gives one value
// per patch; a picture drawn with it shows every patch as a flat tile. Give
// each vertex a radiosity and interpolate across each patch (Gouraud) instead.
//
//   patch_own   – the trivial solution: each corner takes its own patch's B
//                 (flat tiles, the notes' "no hay buenos resultados");
//   average     – a vertex takes the mean B of every face of its smooth group
//                 that touches it (as a corner or, for a T-vertex, through an edge);
//   extrapolate – average inside a wall; on a wall's edge and corner the
//                 average would pull the vertex towards the inside, so
//                 extrapolate past it (lesson 12, §3):
//                   edge vertex b of faces 1, 2 sharing the edge b–e:  B_b = B₁ + B₂ − B_e
//                   corner vertex a of quad 1, opposite vertex e:        B_a = 2B₁ − B_e
//                 with B_e the *average* value of e, then clamp each channel
//                 at zero (a radiosity is never negative; the extrapolation
//                 of a steep gradient can be).
// Every other boundary vertex (three or more faces, a triangle's corner,
// faces that share no edge at the vertex) keeps its average. Any vertex can
// be e, vertex 0 included.
//
// The faces are mesh.faces[0 … faces.size() − 1], exactly: a mesh edited in
// place (a face removed) keeps a std::vector's spare capacity, whose stale
// bytes past the end are no face and must never be read.
//
// T-vertices: after the vertex values are set, each T-vertex takes the value
// interpolated along the edge it lies on, in the mesh's t_vertices order,
// so that the small faces' colours meet the large face's without a jump
// (no crack in the picture).
#include <vector>

#include "illum/core/vec.hpp"
#include "illum/radiosity/patch.hpp"
#include "illum/radiosity/shared_vertex_mesh.hpp"

namespace illum {

enum class VertexColourRule { patch_own, average, extrapolate };

// Task 1. Per vertex of `mesh`: the mean of face_radiosity over the faces that
// list the vertex and the faces whose edge it lies inside (mesh.t_vertices).
// A vertex that no face touches gets 0. Throws std::invalid_argument when
// face_radiosity.size() != mesh.faces.size().
std::vector<Color> average_vertex_radiosity(const SharedVertexMesh& mesh,
                                            const std::vector<Color>& face_radiosity);

// Task 2. Per vertex: the extrapolation rule above, built on Task 1's averages,
// each channel clamped at zero. B_e is always e's *average* (a copy of Task 1's
// result kept apart): a vertex extrapolated earlier in the loop must not change
// a later one's B_e. T-vertices keep their average here (Task 3 sets them).
// Same precondition as Task 1.
std::vector<Color> extrapolated_vertex_radiosity(const SharedVertexMesh& mesh,
                                                 const std::vector<Color>& face_radiosity);

// Task 3. Sets each T-vertex of mesh.t_vertices, in order, to
// (1 − t)·value[from] + t·value[to] (t is measured from `from`: 0 there, 1 at
// `to`), so that a later entry reads an earlier one's result. Throws
// std::invalid_argument when vertex_value.size() != mesh.positions.size().
void resolve_t_vertices(const SharedVertexMesh& mesh, std::vector<Color>& vertex_value);

// Task 4. Per face, per corner (in the order of mesh.faces[f]): the radiosity
// the rule gives, T-vertices resolved (Task 3) for average and for extrapolate
// alike. Throws std::invalid_argument when face_radiosity.size() !=
// mesh.faces.size(), for every rule, patch_own included (which needs no vertex).
std::vector<std::vector<Color>> corner_radiosity(const SharedVertexMesh& mesh,
                                                 const std::vector<Color>& face_radiosity,
                                                 VertexColourRule rule);

// Task 5. Gouraud interpolation inside one face from its corner values:
// bilinear for 4 corners,
//   (1 − u)(1 − v) c₀ + u(1 − v) c₁ + u v c₂ + (1 − u) v c₃,
// barycentric for 3, (1 − u − v) c₀ + u c₁ + v c₂, the weights in double
// (u, v such as 0.1 and 0.7 are not binary fractions). Throws
// std::invalid_argument for another number of corners.
Color gouraud(const std::vector<Color>& corners, double u, double v);

// The radiosity at a point of `patch` from its corner values: gouraud at
// patch_parameters(patch, point).
Color interpolate_radiosity(const Patch& patch, const std::vector<Color>& corners, const Point3& point);

}  // namespace illum
