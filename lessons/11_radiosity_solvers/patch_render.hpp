#pragma once
// Lesson 11's pictures: the Cornell box with one flat colour per patch, by
// casting one ray per pixel against the scene's surfaces (brute force, 17
// polygons) and then against the patches of the surface hit. Not an
// exercise: the lesson is about solving for B, not about drawing it.
// Lesson-local, so in namespace illum::lesson11: the library's namespace
// illum holds only lib/illum/ code.
#include <optional>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/ray.hpp"
#include "illum/radiosity/radiosity_scene.hpp"

namespace illum::lesson11 {

// Parameter s of the hit of `ray` with a planar convex polygon (either side),
// or nothing: the plane hit s = (N·(V0 − P0))/(N·ω) (the sign of erratum 2 of docs/errata.md), then
// the point must lie on the inner side of every edge.
std::optional<double> hit_convex_polygon(const Ray& ray, const std::vector<Point3>& polygon,
                                         const Vec3& normal);

// The index of the patch seen through each pixel (−1: none).
std::vector<int> patch_item_buffer(const RadiosityScene& scene, int width, int height);

// Flat-shaded image: pixel = exposure · B of the patch it sees.
Image flat_patch_image(const std::vector<int>& items, int width, int height,
                       const std::vector<Color>& radiosity, double exposure);

// An exposure that maps the 95th percentile of the non-emitting patches'
// brightest channel to 0.85 (the light itself saturates to white).
double exposure_for(const std::vector<Patch>& patches, const std::vector<Color>& radiosity);

}  // namespace illum::lesson11
