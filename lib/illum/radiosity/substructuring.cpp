#include "illum/radiosity/substructuring.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illum/accel/triangle_accel.hpp"
#include "illum/core/error.hpp"
#include "illum/core/parallel.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_solvers.hpp"

namespace illum {
namespace {

// Rows shorter than this are computed on one thread: a parallel region per
// shot costs a fork and a barrier, which a loaded machine makes slow.
constexpr std::size_t parallel_row_elements = 4096;

std::vector<Patch> split_patch(const Patch& p, int k) {
  const std::vector<Point3>& v = p.vertices;
  if (v.size() == 4) return mesh_quad(v[0], v[1], v[2], v[3], k, k, p.reflectance, p.emission, p.surface);
  require(v.size() == 3, "substructuring: a patch must have 3 or 4 vertices");
  return mesh_triangle(v[0], v[1], v[2], k, p.reflectance, p.emission, p.surface);
}

double power(const Color& c, double area) { return area * (c.r + c.g + c.b); }

// The occluders of the ray-cast row: every polygon as a fan of triangles.
std::unique_ptr<TriangleAccel> occluder_bvh(const std::vector<std::vector<Point3>>& polygons) {
  std::vector<Triangle> triangles;
  for (const std::vector<Point3>& p : polygons)
    for (std::size_t k = 1; k + 1 < p.size(); ++k) triangles.emplace_back(p[0], p[k], p[k + 1]);
  return make_accel(TriangleSet::from_triangles(std::move(triangles)), {.kind = AccelKind::compact_bvh});
}

// row[e] = F_pe by the point-to-disc factor and one shadow ray per element.
void ray_cast_row(const Patch& shooter, const std::vector<Patch>& elements, const TriangleAccel& occluders,
                  std::span<double> row) {
  const auto n = static_cast<std::ptrdiff_t>(elements.size());
  ExceptionCollector errors;  // occluded() may be a student's (lesson 08): its throw reaches the caller
#pragma omp parallel for schedule(static) if (n >= static_cast <std::ptrdiff_t>(parallel_row_elements))
  for (std::ptrdiff_t e = 0; e < n; ++e)
    errors.run([&] {
      const Patch& element = elements[static_cast<std::size_t>(e)];
      const Vec3 d = element.centroid - shooter.centroid;
      const double r2 = dot(d, d);
      const double cos_p = dot(shooter.normal, d), cos_e = -dot(element.normal, d);  // both × r
      row[e] = 0;
      if (!(cos_p > 0 && cos_e > 0)) return;
      const double r = std::sqrt(r2);
      // The segment's ends lie on the shooter and on the element: leave a
      // relative margin so that their own patches never block it.
      TraversalCounters counters;
      if (occluders.occluded(Ray(shooter.centroid, d / r, Interval(1e-7 * r, (1 - 1e-7) * r)), counters))
        return;
      // The shooter as a disc of its own area seen from the element (bounded
      // by 1 however close the element), turned into F_pe by reciprocity.
      const double f_ep = (cos_p / r) * (cos_e / r) * shooter.area / (std::numbers::pi * r2 + shooter.area);
      row[e] = f_ep * element.area / shooter.area;
    });
  errors.rethrow_if_any();
}

}  // namespace

ElementMesh uniform_elements(const std::vector<Patch>& patches, int k) {
  require(k >= 1, "uniform_elements: k must be at least 1");
  ElementMesh mesh;
  for (std::size_t p = 0; p < patches.size(); ++p)
    for (Patch& e : split_patch(patches[p], k)) {
      mesh.elements.push_back(std::move(e));
      mesh.patch_of.push_back(static_cast<int>(p));
    }
  return mesh;
}

ElementMesh split_elements(const ElementMesh& mesh, const std::vector<bool>& split) {
  require(split.size() == mesh.elements.size(), "split_elements: one flag per element is needed");
  ElementMesh out;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    if (!split[e]) {
      out.elements.push_back(mesh.elements[e]);
      out.patch_of.push_back(mesh.patch_of[e]);
      continue;
    }
    for (Patch& child : split_patch(mesh.elements[e], 2)) {
      out.elements.push_back(std::move(child));
      out.patch_of.push_back(mesh.patch_of[e]);
    }
  }
  return out;
}

std::vector<double> longest_edges(const ElementMesh& mesh) {
  std::vector<double> longest;
  for (const Patch& e : mesh.elements) {
    double l = 0;
    for (std::size_t k = 0; k < e.vertices.size(); ++k)
      l = std::max(l, length(e.vertices[(k + 1) % e.vertices.size()] - e.vertices[k]));
    longest.push_back(l);
  }
  return longest;
}

SubstructuredSolution shoot_patches_to_elements(const std::vector<Patch>& patches, const ElementMesh& mesh,
                                                const ShootingSettings& settings) {
  Stopwatch watch;
  const std::size_t n = mesh.elements.size();
  require(mesh.patch_of.size() == n && n > 0,
          "shoot_patches_to_elements: an empty or inconsistent element mesh");
  for (int p : mesh.patch_of)
    require(p >= 0 && static_cast<std::size_t>(p) < patches.size(),
            "shoot_patches_to_elements: an element names no patch");
  SubstructuredSolution s;
  s.element_radiosity.resize(n);
  for (std::size_t e = 0; e < n; ++e) s.element_radiosity[e] = mesh.elements[e].emission;
  s.patch_unshot.resize(patches.size());
  double emitted = 0;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    s.patch_unshot[p] = patches[p].emission;
    emitted += power(patches[p].emission, patches[p].area);
  }
  require(emitted > 0, "shoot_patches_to_elements: nothing emits");
  const std::size_t max_shots = settings.max_shots > 0 ? settings.max_shots : 200 * patches.size();

  // The hemicube draws the elements and the shooter, appended last so that its own row entry is skipped.
  const bool hemicube = settings.visibility == ShotVisibility::hemicube;
  std::vector<Patch> targets;
  std::unique_ptr<Hemicube> cube;
  std::vector<HemicubeBuffers> buffers;
  std::unique_ptr<TriangleAccel> occluders;
  if (hemicube) {
    cube = std::make_unique<Hemicube>(settings.hemicube_resolution);
    targets = mesh.elements;
    targets.push_back(patches.front());
  } else {
    std::vector<std::vector<Point3>> polygons = settings.occluders;
    if (polygons.empty())
      for (const Patch& p : patches) polygons.push_back(p.vertices);
    occluders = occluder_bvh(polygons);
  }
  std::vector<double> row(n + 1, 0.0);
  s.history.reserve(std::min<std::size_t>(max_shots, 1 << 20));
  double unshot_power = emitted;
  while (unshot_power / emitted >= settings.unshot_fraction && s.shots < max_shots) {
    const std::size_t p = choose_shooter(patches, s.patch_unshot);
    const Patch& shooter = patches[p];
    if (hemicube) {
      targets.back() = shooter;
      if (n >= parallel_row_elements) {
        cube->form_factor_row_parallel(targets, n, row, buffers);
      } else {
        buffers.resize(1);
        cube->form_factor_row(targets, n, row, buffers.front());
      }
    } else {
      ray_cast_row(shooter, mesh.elements, *occluders, row);
    }
    const Color delta = s.patch_unshot[p];
    s.patch_unshot[p] = Color(0.0);
    for (std::size_t e = 0; e < n; ++e) {
      if (row[e] == 0) continue;
      const Patch& element = mesh.elements[e];
      // F_ep = F_pe A_p / A_e is a form factor: never above 1. The hemicube,
      // which treats the shooter as a point, can exceed it for an element
      // close to the shooter's centroid.
      const double f_ep = std::min(1.0, row[e] * shooter.area / element.area);
      const Color gain = element.reflectance * f_ep * delta;
      s.element_radiosity[e] += gain;
      const auto q = static_cast<std::size_t>(mesh.patch_of[e]);
      s.patch_unshot[q] += gain * (element.area / patches[q].area);
    }
    ++s.shots;
    unshot_power = 0;
    for (std::size_t q = 0; q < patches.size(); ++q)
      unshot_power += power(s.patch_unshot[q], patches[q].area);
    s.history.push_back({s.shots, watch.seconds(), unshot_power / emitted});
    while (s.snapshots.size() < settings.snapshot_unshot.size() &&
           unshot_power / emitted < settings.snapshot_unshot[s.snapshots.size()]) {
      const Color ambient = ambient_term(patches, s.patch_unshot);
      std::vector<Color>& shown = s.snapshots.emplace_back(s.element_radiosity);
      for (std::size_t e = 0; e < n; ++e) shown[e] += mesh.elements[e].reflectance * ambient;
    }
  }
  s.unshot_fraction = unshot_power / emitted;
  s.seconds = watch.seconds();
  return s;
}

}  // namespace illum
