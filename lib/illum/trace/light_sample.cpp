#include "illum/trace/light_sample.hpp"

#include "illum/core/error.hpp"

namespace illum {

std::size_t light_count(const Scene& scene) { return scene.point_lights.size() + scene.area_lights.size(); }

LightSample light_sample(const Scene& scene, std::size_t light) {
  require(light < light_count(scene), "light_sample: no such light");
  if (light < scene.point_lights.size()) {
    const PointLight& p = scene.point_lights[light];
    return {p.position, p.intensity};
  }
  const AreaLight& a = scene.area_lights[light - scene.point_lights.size()];
  Point3 centroid(0.0);
  for (const Point3& v : a.polygon) centroid += v;
  return {centroid / static_cast<double>(a.polygon.size()), a.emission};
}

}  // namespace illum
