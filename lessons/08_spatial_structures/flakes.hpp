#pragma once
// Lesson 08's test scene and its measurements: deterministic sphereflakes
// (accel/sphereflake.hpp) of about N triangles, the camera and rays that look
// at them, the cost per ray of a structure (counted, and timed on one
// thread), the knob studies of §6, and the shaded picture of the
// demonstration. Shared by main.cpp and the studies.
#include <cstddef>
#include <vector>

#include "illum/accel/triangle_accel.hpp"
#include "illum/accel/triangle_set.hpp"
#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/io/output_folder.hpp"

namespace illum::lesson08 {

inline constexpr const char* program_id = "lesson08";

// The sphereflake whose triangle count comes nearest `triangles`.
TriangleSet flake_with_about(std::size_t triangles);

// The camera every picture and camera ray of the lesson uses.
PinholeCamera flake_camera(int width, int height);

// One ray through the centre of each pixel of a size × size image.
std::vector<Ray> camera_rays(int size);

// What a structure costs on the camera rays.
struct Measure {
  double build_seconds = 0.0, bytes_per_triangle = 0.0, nodes_per_ray = 0.0, tests_per_ray = 0.0,
         mrays_per_second = 0.0;
};

// Builds one structure, counts its work on `rays` once, then times closest-hit
// queries on one thread (the best of three, best_nanoseconds_per_call, each at
// least `min_seconds`).
Measure measure(const TriangleSet& set, const AccelSettings& settings, const std::vector<Ray>& rays,
                double min_seconds);

// One structure's knob swept on the same sphereflake and camera rays: build
// cost and memory against nodes (or cells) and triangle tests per ray (§6).
struct KnobStudy {
  const char* name;   // the table's (and plot's) file name
  const char* knob;   // the knob's column header
  const char* nodes;  // the header of the nodes-or-cells-per-ray column
  std::vector<int> quick_values, values;
  AccelSettings (*settings)(int knob);
  const char* caption;
};

// Writes the knob study's table.
void knob_study(OutputFolder& out, bool quick, const KnobStudy& study);

// The plot of a knob study: nodes (or cells) walked against triangles tested.
void plot_knob_study(OutputFolder& out, const KnobStudy& study, const std::string& title,
                     const std::string& x_label, const std::string& nodes_title, const std::string& caption);

// The demonstration's picture: its size and samples per pixel (side × side).
struct PictureSize {
  int width, height, side;
};
// 640 × 480 at 4 × 4 samples a pixel (96 × 72, one sample, with --quick): long
// enough that §6's timing of it is about a second or more.
PictureSize picture_size(bool quick);

// One render of the picture through `accel` on `threads` threads: each pixel
// the mean of side × side samples, each the Lambert term of the closest hit
// darkened where a shadow ray (any hit) is blocked.
struct FlakePicture {
  Image image{1, 1};
  TraversalCounters counters;      // every thread's, added up
  double busiest_cpu_seconds = 0;  // the processor time of the thread that worked longest
};
FlakePicture render_flake(const TriangleAccel& accel, const PinholeCamera& camera, int side, int threads);

}  // namespace illum::lesson08
