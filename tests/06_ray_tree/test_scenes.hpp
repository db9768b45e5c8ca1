#pragma once
// Small scenes built in code for the lesson-06 tests, each simple enough that
// the colour of a ray can be worked out by hand.
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "illum/trace/optics.hpp"
#include "illum/trace/scene.hpp"

namespace illum::test {

inline Material material(const std::string& name) { return Material{.name = name}; }

inline std::uint32_t add_material(Scene& scene, const Material& m) {
  scene.materials.push_back(m);
  return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

inline void add_sphere(Scene& scene, const std::string& name, const Point3& centre, double radius,
                       std::uint32_t material) {
  scene.primitives.push_back(Primitive{.name = name, .shape = Sphere(centre, radius), .material = material});
}

// The square [−h, h]² of the plane z = z0, normal +z (counter-clockwise seen from above).
inline void add_floor(Scene& scene, const std::string& name, double z0, double h, std::uint32_t material) {
  scene.primitives.push_back(Primitive{
      .name = name,
      .shape = Polygon({Point3(-h, -h, z0), Point3(h, -h, z0), Point3(h, h, z0), Point3(-h, h, z0)}),
      .material = material});
}

inline void add_light(Scene& scene, const Point3& position, const Color& intensity) {
  scene.point_lights.push_back(PointLight{.name = "light", .position = position, .intensity = intensity});
}

// A surface hit made by hand: the point (exact, error bound a few ulps), the
// normal facing the side the ray came from, and a material.
inline SurfaceHit hand_hit(const Point3& point, const Vec3& normal, std::uint32_t material) {
  SurfaceHit hit;
  hit.t = 1.0;
  hit.point = point;
  hit.point_error = Vec3(1e-15) * (Vec3(1.0) + glm::abs(point));
  hit.geometric_normal = hit.shading_normal = normal;
  hit.front_face = true;
  hit.primitive = 0;
  hit.material = material;
  return hit;
}

// A vector or colour checked component by component, with both values in the
// failure message.
inline void check_vec(const Vec3& got, const Vec3& want, double eps = 1e-12) {
  INFO("got (", got.x, ", ", got.y, ", ", got.z, "), expected (", want.x, ", ", want.y, ", ", want.z, ")");
  CHECK(got.x == doctest::Approx(want.x).epsilon(eps).scale(1.0));
  CHECK(got.y == doctest::Approx(want.y).epsilon(eps).scale(1.0));
  CHECK(got.z == doctest::Approx(want.z).epsilon(eps).scale(1.0));
}

// The directions a test needs from Tasks 1 and 2, checked before it traces: a wrong
// reflect or refract then fails here, naming the task and the formula, rather than
// later in spawn_ray or as a wrong colour.
inline void require_reflect(const Vec3& incoming, const Vec3& normal, const Vec3& want) {
  const Vec3 got = reflect(incoming, normal);
  INFO("this test traces a mirror, so it needs Task 1 first: reflect(I, N) with I = (", incoming.x, ", ",
       incoming.y, ", ", incoming.z, ") and N = (", normal.x, ", ", normal.y, ", ", normal.z,
       ") is R = I − 2(N·I)N = (", want.x, ", ", want.y, ", ", want.z, "); got (", got.x, ", ", got.y, ", ",
       got.z, ")");
  REQUIRE(glm::length(got - want) < 1e-12);
}

inline void require_refract(const Vec3& incoming, const Vec3& normal, double eta_ratio, const Vec3& want) {
  const Refraction got = refract(incoming, normal, eta_ratio);
  INFO("this test traces glass, so it needs Task 2 first: refract(I, N, η_i/η_t = ", eta_ratio,
       ") with I = (", incoming.x, ", ", incoming.y, ", ", incoming.z, ") and N = (", normal.x, ", ",
       normal.y, ", ", normal.z, ") is T = (", want.x, ", ", want.y, ", ", want.z, ") by Snell's law; got ",
       got.total_internal_reflection ? std::string("total internal reflection") : std::string("a direction"),
       " (", got.direction.x, ", ", got.direction.y, ", ", got.direction.z, ")");
  REQUIRE(!got.total_internal_reflection);
  REQUIRE(glm::length(got.direction - want) < 1e-12);
}

}  // namespace illum::test
