#pragma once
// Lesson 05's surfaces on screen: the shading, the implicit-surface renderer
// and the patches the demonstration draws, shared by main.cpp and the
// studies (a thin feature, the subdivision depth).
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/geometry/bezier_patch.hpp"
#include "illum/geometry/implicit_surface.hpp"
#include "illum/geometry/implicit_trace.hpp"

namespace illum::lesson05 {

inline const Color background(0.06, 0.07, 0.09);

// Lambert plus a little ambient, from a light above the camera's left shoulder;
// the normal is turned to face the viewer (patches have two sides).
Color shade(const Vec3& normal, const Vec3& direction, const Color& albedo);

// One primary ray per pixel against `surface` by `method` (geometry/implicit_trace.hpp), shaded.
Image render_implicit(const PinholeCamera& camera, const ImplicitSurface& surface, ImplicitMethod method,
                      const ImplicitOptions& options, const Color& albedo);

// A bicubic height-field-like patch with a bump ("wavy") and a bilinear saddle.
std::vector<BezierPatch> demo_patches();

// The camera the torus pictures share.
PinholeCamera torus_camera(int width, int height);

}  // namespace illum::lesson05
