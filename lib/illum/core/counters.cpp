#include "illum/core/counters.hpp"

namespace illum {

WorkCounters& WorkCounters::operator+=(const WorkCounters& o) {
  rays_cast += o.rays_cast;
  primary_rays += o.primary_rays;
  shadow_rays += o.shadow_rays;
  secondary_rays += o.secondary_rays;
  intersection_tests += o.intersection_tests;
  hits += o.hits;
  return *this;
}

std::string WorkCounters::summary() const {
  return "rays " + std::to_string(rays_cast) + " (primary " + std::to_string(primary_rays) + ", shadow " +
         std::to_string(shadow_rays) + ", secondary " + std::to_string(secondary_rays) + "); tests " +
         std::to_string(intersection_tests) + "; hits " + std::to_string(hits);
}

}  // namespace illum
