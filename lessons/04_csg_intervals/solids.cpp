#include "solids.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace illum::lesson04 {

CsgNodePtr make_die() {
  const CsgNodePtr rounded = csg_intersection(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                                              csg_solid(SolidSphere(Point3(0), 1.38), body));
  struct Face {
    Vec3 normal, u, v;
    int count;
  };
  const std::array<Face, 6> faces{{{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 1},
                                   {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}, 6},
                                   {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 2},
                                   {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 5},
                                   {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, 3},
                                   {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}, 4}}};
  std::vector<CsgNodePtr> pips;
  for (const Face& face : faces) {
    // Pip positions on the face, in units of the face's half width.
    std::vector<Vec2> at;
    const int n = face.count;
    if (n % 2 == 1) at.push_back(Vec2(0, 0));
    if (n >= 2) at.push_back(Vec2(-0.5, -0.5)), at.push_back(Vec2(0.5, 0.5));
    if (n >= 4) at.push_back(Vec2(-0.5, 0.5)), at.push_back(Vec2(0.5, -0.5));
    if (n == 6) at.push_back(Vec2(-0.5, 0)), at.push_back(Vec2(0.5, 0));
    for (const Vec2& p : at) {
      pips.push_back(csg_solid(SolidSphere(1.06 * face.normal + p.x * face.u + p.y * face.v, 0.2), pip));
    }
  }
  return csg_difference(rounded, csg_union_all(pips));
}

CsgNodePtr make_lens() {
  return csg_intersection(csg_solid(SolidSphere(Point3(0, 0, 0.6), 1.0), body),
                          csg_solid(SolidSphere(Point3(0, 0, -0.6), 1.0), second));
}

CsgNodePtr make_drilled_cube() {
  const auto drill = [](const Vec3& axis, int tag) {
    return csg_solid(SolidCylinder(-1.5 * axis, axis, 0.45, 3.0), tag);
  };
  return csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                        csg_union(drill(Vec3(1, 0, 0), drill_x),
                                  csg_union(drill(Vec3(0, 1, 0), drill_y), drill(Vec3(0, 0, 1), drill_z))));
}

CsgNodePtr make_blind_hole() {
  return csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                        csg_solid(SolidCylinder(Point3(0, 0, 0), Vec3(0, 0, 1), 0.5, 1.0), drill_y));
}

CsgNodePtr make_pocket() {
  return csg_difference(csg_solid(SolidBox(Point3(-1), Point3(1)), body),
                        csg_solid(SolidBox(Point3(-0.5, -0.5, 0), Point3(0.5, 0.5, 1)), drill_y));
}

CsgNodePtr make_coin() {
  return csg_intersection(
      csg_solid(SolidSlab(Vec3(0, 0, 1), -0.5 * coin_thickness, 0.5 * coin_thickness), body),
      csg_solid(SolidSphere(Point3(0), 1.0), body));
}

Color background(const Ray& ray) { return Color(0.05, 0.06, 0.08) + 0.12 * (0.5 + 0.5 * ray.direction.z); }

Color shade(const Ray& ray, const CsgHit& hit) {
  static const std::array<Color, 4> palette{Color(0.85, 0.82, 0.74), Color(0.55, 0.08, 0.06),
                                            Color(0.15, 0.45, 0.75), Color(0.2, 0.6, 0.25)};
  const Vec3 light = normalize(Vec3(0.4, -0.7, 1.0));
  Vec3 n = hit.normal;
  if (dot(n, ray.direction) > 0.0) n = -n;  // seen from inside: light the side facing the eye
  const Color base = palette[static_cast<std::size_t>(hit.surface) % palette.size()];
  return base * (0.15 + 0.85 * std::max(0.0, dot(n, light)));
}

Color normal_colour(const Ray&, const CsgHit& hit) { return 0.5 * (hit.normal + Vec3(1.0)); }

}  // namespace illum::lesson04
