#include "illum/trace/light_sample.hpp"

#include <algorithm>
#include <numbers>

#include "illum/core/error.hpp"

namespace illum {

std::size_t light_count(const Scene& scene) { return scene.point_lights.size() + scene.area_lights.size(); }

LightSample light_sample(const Scene& scene, std::size_t light, const Point3& at) {
  require(light < light_count(scene), "light_sample: no such light");
  if (light < scene.point_lights.size()) {
    const PointLight& p = scene.point_lights[light];
    return {p.position, p.intensity};
  }
  const AreaLight& a = scene.area_lights[light - scene.point_lights.size()];
  Point3 centroid(0.0);
  Vec3 twice_area(0.0);  // Newell's normal: its length is twice the polygon's area
  for (std::size_t i = 0; i < a.polygon.size(); ++i) {
    centroid += a.polygon[i];
    twice_area += cross(a.polygon[i], a.polygon[(i + 1) % a.polygon.size()]);
  }
  centroid /= static_cast<double>(a.polygon.size());
  const Vec3 to_point = at - centroid;
  const double r2 = length_squared(to_point);
  if (!(r2 > 0.0)) return {centroid, Color(0.0)};
  // A·cos θ_l = (twice_area/2)·(to_point/r); divided by π r².
  const double projected = std::max(0.0, 0.5 * dot(twice_area, to_point) / std::sqrt(r2));
  return {centroid, a.emission * (projected / (std::numbers::pi * r2))};
}

}  // namespace illum
