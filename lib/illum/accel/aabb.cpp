#include "illum/accel/aabb.hpp"

namespace illum {

int Aabb::longest_axis() const {
  const Vec3 e = extent();
  return (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
}

double Aabb::surface_area() const {
  if (empty()) return 0.0;
  const Vec3 e = extent();
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

Aabb bounds_of(const Triangle& t) {
  Aabb box;
  box.grow(t.a);
  box.grow(t.b);
  box.grow(t.c);
  return box;
}

}  // namespace illum
