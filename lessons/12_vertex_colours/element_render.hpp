#pragma once
// Lesson 12's pictures: the Cornell box through a camera, each pixel showing
// the element it sees, shaded from that element's corner radiosities
// (Gouraud). Lesson-local, in namespace illum::lesson12: the library's
// namespace illum holds only lib/illum/ code.
#include <vector>

#include "illum/core/image.hpp"
#include "illum/radiosity/radiosity_scene.hpp"
#include "illum/radiosity/substructuring.hpp"

namespace illum::lesson12 {

// For each pixel: the element seen (−1: none) and the point hit on it.
struct ElementView {
  int width = 0, height = 0;
  std::vector<int> element;
  std::vector<Point3> point;
};

// One ray per pixel against the scene's surfaces (brute force, a few
// polygons), then against the patches of the surface hit and the elements
// of that patch: a few dozen tests per pixel instead of one per element.
ElementView view_elements(const RadiosityScene& scene, const ElementMesh& mesh, const RadiosityCamera& camera,
                          int width, int height);

// pixel = exposure · the Gouraud value at the pixel's point from the element's corners.
Image gouraud_image(const ElementView& view, const ElementMesh& mesh,
                    const std::vector<std::vector<Color>>& corners, double exposure);

// Maps the 95th percentile of the non-emitting elements' brightest channel to 0.85.
double exposure_for(const ElementMesh& mesh, const std::vector<Color>& radiosity);

// Whether `point` (on the element's plane) lies inside the convex element,
// edges included with a tolerance relative to the element's size.
bool element_contains(const Patch& element, const Point3& point);

}  // namespace illum::lesson12
