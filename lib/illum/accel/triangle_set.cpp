#include "illum/accel/triangle_set.hpp"

#include <sstream>

#include "illum/core/error.hpp"

namespace illum {
namespace {

std::string describe(const Point3& p) {
  std::ostringstream s;
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

}  // namespace

TriangleSet TriangleSet::from_mesh(std::span<const Point3> vertices, std::span<const Face> faces,
                                   const std::string& name) {
  for (std::size_t v = 0; v < vertices.size(); ++v)
    if (!is_finite(vertices[v]))
      throw InputError(name, "vertices[" + std::to_string(v) + "]", describe(vertices[v]),
                       "a vertex must be finite (no NaN or infinity)");
  TriangleSet set;
  set.triangles.reserve(faces.size());
  set.face_of.reserve(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k)
      if (faces[f][k] >= vertices.size())
        throw InputError(name, "faces[" + std::to_string(f) + "][" + std::to_string(k) + "]",
                         std::to_string(faces[f][k]),
                         "index past the last of " + std::to_string(vertices.size()) + " vertices");
    const Point3 &a = vertices[faces[f][0]], &b = vertices[faces[f][1]], &c = vertices[faces[f][2]];
    if (cross(b - a, c - a) == Vec3(0.0)) {  // the same exact test as Triangle's constructor
      set.degenerate.push_back(static_cast<std::uint32_t>(f));
      continue;
    }
    set.triangles.emplace_back(a, b, c);
    set.face_of.push_back(static_cast<std::uint32_t>(f));
  }
  return set;
}

TriangleSet TriangleSet::from_triangles(std::vector<Triangle> triangles) {
  TriangleSet set;
  set.face_of.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) set.face_of[i] = static_cast<std::uint32_t>(i);
  set.triangles = std::move(triangles);
  return set;
}

}  // namespace illum
