// Exercise unit of lesson 03 (exercises/03_orientation_convex/triangle.cpp is its stub).
#include "illum/geometry/triangle.hpp"

#include <cmath>
#include <utility>

#include "illum/geometry/orientation.hpp"

namespace illum {

std::optional<TriangleHit> intersect(const Ray& ray, const Triangle& triangle) {
  const Vec3& d = ray.direction;
  // The ray frame: kz is the direction's largest component; kx, ky follow it
  // cyclically, swapped when d[kz] < 0 so that the triangle's winding is kept.
  const Vec3 ad = glm::abs(d);
  const int kz = (ad.x >= ad.y && ad.x >= ad.z) ? 0 : (ad.y >= ad.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0.0) std::swap(kx, ky);
  const double shear_x = d[kx] / d[kz], shear_y = d[ky] / d[kz], scale_z = 1.0 / d[kz];

  // Each vertex relative to the origin, sheared so that the ray is the z axis.
  const Vec3 pa = triangle.a - ray.origin, pb = triangle.b - ray.origin, pc = triangle.c - ray.origin;
  const Vec2 a2(pa[kx] - shear_x * pa[kz], pa[ky] - shear_y * pa[kz]);
  const Vec2 b2(pb[kx] - shear_x * pb[kz], pb[ky] - shear_y * pb[kz]);
  const Vec2 c2(pc[kx] - shear_x * pc[kz], pc[ky] - shear_y * pc[kz]);

  // Exact signs of the edge functions at the ray (the 2D origin), ties broken
  // by the symbolic perturbation shared by every triangle.
  const Vec2 origin(0.0);
  const int su = orient2d_sign_perturbed(b2, c2, origin);
  const int sv = orient2d_sign_perturbed(c2, a2, origin);
  const int sw = orient2d_sign_perturbed(a2, b2, origin);
  if (su == 0 || su != sv || su != sw) return std::nullopt;  // outside, or seen edge-on

  // The edge functions' values (their sign is settled above): unnormalised barycentrics.
  const double u = b2.x * c2.y - b2.y * c2.x;
  const double v = c2.x * a2.y - c2.y * a2.x;
  const double w = a2.x * b2.y - a2.y * b2.x;
  const double det = u + v + w;
  if (det == 0.0) return std::nullopt;  // the triangle is seen edge-on

  // The hit's depth along the ray: the barycentric blend of the vertices' z.
  const double s = (u * pa[kz] + v * pb[kz] + w * pc[kz]) * scale_z / det;
  if (!ray.range.contains(s)) return std::nullopt;

  TriangleHit hit;
  hit.s = s;
  hit.point = ray.at(s);
  hit.barycentric = Vec3(u, v, w) / det;
  hit.normal = triangle.normal();
  return hit;
}

}  // namespace illum
