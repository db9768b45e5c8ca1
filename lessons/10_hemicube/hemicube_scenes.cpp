#include "hemicube_scenes.hpp"

#include <cmath>

#include "illum/core/frame.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/hemicube_deltas.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"

namespace illum::lesson10 {

double parallel_corner(double a, double b, double c) { return top_face_corner(a / c, b / c); }

double perpendicular_corner(double a, double b, double c) { return side_face_corner(b / c, a / c); }

double exact_from_origin(const Patch& target) {
  return point_polygon_form_factor(Point3(0), Vec3(0, 0, 1), target);
}

Patch facing_origin(const std::vector<Point3>& polygon) {
  Patch target = make_patch(polygon);
  if (dot(target.normal, target.centroid) > 0)
    target = make_patch(std::vector<Point3>(polygon.rbegin(), polygon.rend()));
  return target;
}

void add_box(std::vector<Patch>& patches, const Point3& lo, const Point3& hi, int m, bool inward,
             int first_surface) {
  const double q[6][4][3] = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}},
      {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}},
      {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}};
  for (int f = 0; f < 6; ++f) {
    Point3 c[4];
    for (int k = 0; k < 4; ++k) c[k] = lo + (hi - lo) * Vec3(q[f][k][0], q[f][k][1], q[f][k][2]);
    auto face = inward ? mesh_quad(c[0], c[1], c[2], c[3], m, m, Color(0.5), Color(0.0), first_surface + f)
                       : mesh_quad(c[0], c[3], c[2], c[1], m, m, Color(0.5), Color(0.0), first_surface + f);
    patches.insert(patches.end(), face.begin(), face.end());
  }
}

std::vector<Patch> room_with_block(int m, int k) {
  std::vector<Patch> patches;
  add_box(patches, Point3(0), Point3(1), m, true, 0);
  add_box(patches, Point3(0.3, 0.35, 0.25), Point3(0.65, 0.7, 0.6), k, false, 6);
  return patches;
}

std::vector<Point3> facing_square(const Point3& c, double s) {
  const Vec3 n = normalize(-c);
  const Frame frame = Frame::from_helper(n, std::abs(n.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0));
  const Vec3 u = frame.t1, v = frame.t2;
  const double h = 0.5 * s;
  return {c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v};
}

Patch receiver_at_origin(double half) {
  return make_patch({{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}});
}

}  // namespace illum::lesson10
