#pragma once
// A strict reader of the OBJ files a scene's meshes name (docs/scene-format.md,
// "OBJ meshes"): vertices, normals and polygonal faces, every line checked.
//
//   const TriangleMesh mesh = read_obj(text);   // InputFileError: "line 12: vertex index 4294967299 ..."
//
// A first pass checks every line and counts what the mesh will hold without
// allocating anything; the memory it will take is checked against the
// budget (system/memory_budget) before the second pass fills it. So a file
// of ten million faces whose last line is cut off is refused after a scan,
// not after gigabytes of allocations, and no number is ever read by halves:
// `v 0 one 1`, `v nan 1 0`, an index of 4294967299 or 99999999999999999999,
// a face of two corners, a free-form curve are each refused with the line,
// the item and the value as written.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include "illum/geometry/triangle_mesh.hpp"
#include "illum/system/input_file.hpp"

namespace illum {

// What the reader reads: `v x y z` (also `v x y z w` and `v x y z r g b`, whose
// extra numbers are ignored), `vn x y z`, `vt u [v [w]]`, and `f` with three
// or more corners `v`, `v/t`, `v//n` or `v/t/n` (1-based indices; negative
// ones count back from the last element defined before the line). `o`, `g`,
// `s`, `usemtl`, `mtllib`, `l`, `p` and the display statements are skipped;
// free-form geometry and unknown statements are refused.
//
// Faces become triangles as a fan from their first corner (exact for the
// convex faces exporters write); a face with a repeated or collinear
// corner that makes a fan triangle of zero area is refused. When every
// corner names a normal, corner_normals holds them (unit), else it is empty.
// An index must fit the vertices a file defines (at most 2^32 − 1); a vertex's x, y and z lie
// within ±max_obj_coordinate. A UTF-8 byte-order mark at the start of the file is skipped.
// A refused file throws InputFileError, "line N: <problem>" (no line for the
// whole file), which the scene reader turns into an InputError naming the field.
TriangleMesh read_obj(std::string_view text);

// The largest |coordinate| of a vertex, as of every point of a scene (a camera's eye, a sphere's
// centre): the squared distances and the areas computed from them then stay within a double.
inline constexpr double max_obj_coordinate = 1e150;

// Bytes a scene holds per triangle of a mesh: the indices, three corner
// normals and the acceleration structure built over it. Measured: `illum
// render` of a 10,000,000-triangle OBJ peaked at 5.3 GB (/usr/bin/time, max RSS).
inline constexpr double obj_bytes_per_triangle = 512.0;

}  // namespace illum
