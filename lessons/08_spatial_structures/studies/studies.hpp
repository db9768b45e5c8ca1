#pragma once
// Lesson 08's studies, one file each, named and numbered by the section of
// README.md that quotes it; main.cpp (the demonstration: a sphereflake
// rendered through the structure --accel names) calls them in the text's order.
#include "illum/accel/triangle_accel.hpp"
#include "illum/core/image.hpp"
#include "illum/io/output_folder.hpp"

namespace illum::lesson08 {

// What the command line sets.
struct Settings {
  bool quick = false;                        // --quick: small sizes
  AccelKind accel = AccelKind::compact_bvh;  // --accel: the structure the demonstration renders through
};

// §1: primary visibility by the item buffer against rays (studies/s01_item_buffer.cpp).
void s01_item_buffer(OutputFolder& out, const Settings& settings);

// §1: shadow rays by the light buffer against any-hit rays (studies/s01_light_buffer.cpp).
void s01_light_buffer(OutputFolder& out, const Settings& settings);

// §2: bounding volumes, tightness against cost (studies/s02_bounding_volumes.cpp).
void s02_bounding_volumes(OutputFolder& out, const Settings& settings);

// §5: the teaching and the production traversal of one BVH (studies/s05_bvh_layouts.cpp).
void s05_bvh_layouts(OutputFolder& out, const Settings& settings);

// §6: cost per ray against the scene's size, every structure (studies/s06a_scaling.cpp).
void s06a_scaling(OutputFolder& out, const Settings& settings);

// §6: the grid's resolution swept (studies/s06b_grid_resolution.cpp).
void s06b_grid_resolution(OutputFolder& out, const Settings& settings);

// §6: the BVH's leaf size swept (studies/s06c_bvh_leaf_size.cpp).
void s06c_bvh_leaf_size(OutputFolder& out, const Settings& settings);

// §6: the octree's depth swept (studies/s06d_octree_depth.cpp).
void s06d_octree_depth(OutputFolder& out, const Settings& settings);

// §6: the demonstration's picture on one thread and on two
// (studies/s06e_render_threads.cpp); `picture` is what both must draw.
void s06e_render_threads(OutputFolder& out, const Settings& settings, const TriangleAccel& accel,
                         const Image& picture);

// §8: lesson 09's Monte Carlo form factors with the visibility by brute force
// and through a BVH (studies/s08_form_factor_visibility.cpp).
void s08_form_factor_visibility(OutputFolder& out, const Settings& settings);

}  // namespace illum::lesson08
