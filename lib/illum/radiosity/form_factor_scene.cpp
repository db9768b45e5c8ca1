#include "illum/radiosity/form_factor_scene.hpp"

#include <cmath>

#include "illum/core/error.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"

namespace illum {

std::vector<Patch> mesh_cube_interior(int n) {
  require(n >= 1, "mesh_cube_interior: n must be at least 1");
  const Color rho(0.5);
  std::vector<Patch> all;
  auto face = [&](Point3 a, Point3 b, Point3 c, Point3 d, int id) {
    auto patches = mesh_quad(a, b, c, d, n, n, rho, Color(0.0), id);
    all.insert(all.end(), patches.begin(), patches.end());
  };
  // Each face counter-clockwise as seen from inside the cube (normal inwards).
  face({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, 0);  // x = 0, normal +x
  face({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, 1);  // x = 1, normal −x
  face({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, 2);  // y = 0, normal +y
  face({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, 3);  // y = 1, normal −y
  face({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 4);  // z = 0, normal +z
  face({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 5);  // z = 1, normal −z
  return all;
}

namespace {

bool coplanar(const Patch& a, const Patch& b) {
  return dot(a.normal, b.normal) > 1 - 1e-12 && std::abs(dot(a.normal, b.centroid - a.centroid)) < 1e-12;
}

template <class PairFunction>
FormFactorMatrix fill_matrix(const std::vector<Patch>& patches, PairFunction pair) {
  const std::size_t n = patches.size();
  FormFactorMatrix f(n);
  const auto rows = static_cast<long>(n);
#pragma omp parallel for schedule(dynamic, 4)
  for (long ii = 0; ii < rows; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    for (std::size_t j = i + 1; j < n; ++j) {
      if (coplanar(patches[i], patches[j])) continue;  // F = 0: the contour formula would waste work
      const double fij = pair(patches[i], patches[j]);
      f(i, j) = fij;
      f(j, i) = patches[i].area * fij / patches[j].area;  // reciprocity A_i F_ij = A_j F_ji
    }
  }
  return f;
}

}  // namespace

FormFactorMatrix contour_form_factor_matrix(const std::vector<Patch>& patches,
                                            const ContourOptions& options) {
  return fill_matrix(
      patches, [&](const Patch& a, const Patch& b) { return polygon_polygon_form_factor(a, b, options); });
}

FormFactorMatrix closed_form_rectangle_matrix(const std::vector<Patch>& patches) {
  return fill_matrix(
      patches, [](const Patch& a, const Patch& b) { return axis_aligned_rectangles_form_factor(a, b); });
}

}  // namespace illum
