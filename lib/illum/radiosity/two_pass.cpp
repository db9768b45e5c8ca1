// Two-pass global illumination (lesson 13): the pipeline around the two
// exercise units. Provided code.
#include "illum/radiosity/two_pass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "illum/core/error.hpp"
#include "illum/core/frame.hpp"
#include "illum/core/parallel.hpp"
#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/core/threads.hpp"
#include "illum/radiosity/hemicube.hpp"
#include "illum/radiosity/radiosity_system.hpp"
#include "illum/radiosity/two_pass_shading.hpp"
#include "illum/trace/effects_plan.hpp"
#include "illum/trace/light_sample.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/ray_offset.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace illum {

namespace {

using std::numbers::pi;

double mean(const Color& c) { return (c.r + c.g + c.b) / 3.0; }

bool is_specular(const Material& m) { return max_channel(m.reflectance + m.transmittance) > 0.0; }

// The outer loop of a polygon or triangle primitive, or nothing for other kinds.
std::vector<Point3> planar_vertices(const Primitive& p) {
  if (const auto* polygon = std::get_if<Polygon>(&p.shape)) {
    const auto loop = polygon->loop(0);
    return {loop.begin(), loop.end()};
  }
  if (const auto* t = std::get_if<Triangle>(&p.shape)) return {t->a, t->b, t->c};
  return {};
}

// A meshed surface of pass one: planar, diffuse or emitting, not specular.
bool is_meshed(const Primitive& p, const Material& m) {
  return (p.kind() == PrimitiveKind::polygon || p.kind() == PrimitiveKind::triangle) && !is_specular(m) &&
         (max_channel(m.diffuse) > 0.0 || max_channel(m.emission) > 0.0);
}

// Some vertex of `b` strictly in front of the plane of `a` (beyond rounding of the scene's size).
bool in_front(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  const Vec3 n = cross(a[1] - a[0], a[2] - a[0]);
  const double scale = length(n) * 1e-9 * (1.0 + length(a[0]));
  for (const Point3& p : b)
    if (dot(n, p - a[0]) > scale) return true;
  return false;
}

// A sphere as rings × 2·rings planar patches (quads between two latitudes,
// triangles at the poles), counter-clockwise seen from outside.
void tessellate_sphere(const Sphere& s, int rings, std::vector<Patch>& out) {
  const int segments = 2 * rings;
  auto at = [&](int ring, int segment) {
    const double theta = pi * ring / rings, phi = 2 * pi * segment / segments;
    return s.center +
           s.radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      std::vector<Point3> v;
      if (r != 0) v.push_back(at(r, k + 1));
      v.push_back(at(r, k));
      v.push_back(at(r + 1, k));
      if (r + 1 != rings) v.push_back(at(r + 1, k + 1));
      if (r == 0) v.push_back(at(r, k + 1));
      Patch p = make_patch(v, Color(0.0), Color(0.0), 1e-6);
      if (dot(p.normal, p.centroid - s.center) < 0) {
        std::reverse(v.begin(), v.end());
        p = make_patch(v, Color(0.0), Color(0.0), 1e-6);
      }
      out.push_back(std::move(p));
    }
}

// The patch lesson 13's locate_patch (an exercise) found for a point of `surface`, checked before it
// indexes the surface's patches: a cell past the end or a wrong corner count would read another
// surface's radiosity, or past the arrays, in silence. The message names the mistake.
std::size_t located_patch(const RadiositySurface& surface, const PatchCell& cell, int n, int m) {
  const std::size_t corners = surface.polygon.size();
  if (cell.patch >= surface.patch_count || static_cast<std::size_t>(cell.corners) != corners)
    throw std::logic_error(
        "locate_patch gave patch " + std::to_string(cell.patch) + " with " + std::to_string(cell.corners) +
        " corners for a " +
        (corners == 4 ? "quad meshed " + std::to_string(n) + " × " + std::to_string(m)
                      : "triangle meshed with n = " + std::to_string(n)) +
        ", which has patches 0 … " + std::to_string(surface.patch_count - 1) + " of " +
        std::to_string(corners) +
        " corners: a point on the far edge belongs to the last cell (two_pass_shading.hpp)");
  return surface.first_patch + cell.patch;
}

}  // namespace

std::string TwoPassPlan::summary() const {
  std::string s = "two-pass plan:\n";
  s += plan_line("caustic pass", caustic_pass);
  s += plan_line("radiosity pass", radiosity_pass);
  s += plan_line("reflected rays", reflection);
  s += plan_line("refracted rays", refraction);
  s += plan_line("shadow rays", shadow_rays);
  s += plan_line("depth limit", max_depth);
  return s + reasons;
}

SceneInventory scene_inventory(const Scene& scene) {
  SceneInventory inv;
  inv.point_lights = scene.point_lights.size();
  std::vector<std::vector<Point3>> reflecting;
  for (const Material& m : scene.materials)
    inv.heaviest_specular = std::max(inv.heaviest_specular, max_channel(m.reflectance + m.transmittance));
  for (const Primitive& p : scene.primitives) {
    const Material& m = scene.materials[p.material];
    if (max_channel(m.transmittance) > 0.0)
      ++inv.glass;
    else if (max_channel(m.reflectance) > 0.0)
      ++inv.mirrors;
    if (is_meshed(p, m)) {
      if (max_channel(m.emission) > 0.0) ++inv.emitters;
      if (max_channel(m.diffuse) > 0.0) {
        ++inv.diffuse_surfaces;
        reflecting.push_back(planar_vertices(p));
      }
    } else if (!is_specular(m) && max_channel(m.diffuse) > 0.0) {
      ++inv.other_diffuse;
    }
  }
  for (std::size_t i = 0; i < reflecting.size(); ++i)
    for (std::size_t j = i + 1; j < reflecting.size(); ++j)
      if (in_front(reflecting[i], reflecting[j]) && in_front(reflecting[j], reflecting[i]))
        ++inv.facing_pairs;
  return inv;
}

TwoPassMesh mesh_two_pass_scene(const Scene& scene, const std::string& file, double max_patch_edge,
                                int sphere_rings) {
  require(sphere_rings >= 2, "mesh_two_pass_scene: a sphere needs at least 2 rings");
  TwoPassMesh mesh;
  mesh.surface_of_primitive.assign(scene.primitives.size(), -1);
  std::vector<Patch> occluders;
  for (std::size_t k = 0; k < scene.primitives.size(); ++k) {
    const Primitive& p = scene.primitives[k];
    const Material& m = scene.materials[p.material];
    const std::string field = "primitives[" + std::to_string(k) + "]";
    std::vector<Point3> v = planar_vertices(p);
    if (is_meshed(p, m)) {
      if (const auto problem = radiosity_polygon_problem(v, max_channel(m.emission) > 0.0))
        throw InputError(file, field, p.name, "pass one cannot mesh it: " + problem->message);
      if (!(max_channel(m.diffuse) < 1.0))
        throw InputError(file, field + ".material", m.name,
                         "a diffuse reflectance must be below 1 for the radiosity pass");
      mesh.surface_of_primitive[k] = static_cast<int>(mesh.radiosity.surfaces.size());
      mesh.radiosity.surfaces.push_back({p.name, m.name, v, m.diffuse, m.emission, 0, 0});
    } else if (const auto* sphere = std::get_if<Sphere>(&p.shape)) {
      tessellate_sphere(*sphere, sphere_rings, occluders);
    } else if (!v.empty() && !radiosity_polygon_problem(v, false)) {
      occluders.push_back(make_patch(v, Color(0.0), Color(0.0), 1e-6));
    } else {
      throw InputError(file, field, p.name,
                       "lesson 13's radiosity pass takes polygons, triangles and spheres only, not a " +
                           std::string(to_string(p.kind())));
    }
  }
  mesh_radiosity_surfaces(mesh.radiosity, max_patch_edge);
  for (const RadiositySurface& s : mesh.radiosity.surfaces) {
    const PatchGrid g = radiosity_patch_grid(s.polygon, max_patch_edge);
    mesh.grid.push_back({static_cast<int>(g.nu), static_cast<int>(g.nv)});
  }
  mesh.receiver_patches = mesh.radiosity.patches.size();
  mesh.occluder_patches = occluders.size();
  for (Patch& p : occluders) mesh.radiosity.patches.push_back(std::move(p));
  return mesh;
}

RadiosityPass solve_radiosity_pass(const std::vector<Patch>& patches, int hemicube_resolution,
                                   double threshold, const std::vector<Color>& extra_emission) {
  require(extra_emission.empty() || extra_emission.size() == patches.size(),
          "solve_radiosity_pass: one extra emission per patch");
  Stopwatch watch;
  std::vector<Patch> lit = patches;
  for (std::size_t i = 0; i < extra_emission.size(); ++i) lit[i].emission += extra_emission[i];
  RadiosityPass pass;
  pass.state = progressive_start(lit);
  const double emitted = total_power(lit, pass.state.unshot);
  if (!(emitted > 0)) {
    pass.unshot = 0;
    pass.seconds = watch.seconds();
    return pass;
  }
  // One thread per row: a row over a few thousand patches takes well under a millisecond,
  // and splitting it (form_factor_row_parallel) costs a barrier per shot, which on a loaded
  // machine waits for a descheduled thread far longer than the row itself.
  const Hemicube hemicube(hemicube_resolution);
  HemicubeBuffers buffers;
  std::vector<double> row(lit.size());
  const std::size_t max_shots = 1000 * lit.size();
  while (pass.unshot >= threshold) {
    if (pass.state.shots >= max_shots)
      throw std::runtime_error("solve_radiosity_pass: the unshot power did not fall below the threshold");
    const std::size_t i = choose_shooter(lit, pass.state.unshot);
    hemicube.form_factor_row(lit, i, row, buffers);
    ++pass.hemicube_rows;
    shoot(lit, i, row, pass.state);
    pass.unshot = total_power(lit, pass.state.unshot) / emitted;
  }
  pass.seconds = watch.seconds();
  return pass;
}

CornerRadiosity flat_corners(const std::vector<Color>& radiosity) {
  CornerRadiosity corners(radiosity.size());
  for (std::size_t i = 0; i < radiosity.size(); ++i) corners[i].fill(radiosity[i]);
  return corners;
}

CornerRadiosity vertex_corners(const TwoPassMesh& mesh, const std::vector<Color>& radiosity,
                               VertexColourRule rule) {
  require(radiosity.size() == mesh.radiosity.patches.size(), "vertex_corners: one radiosity per patch");
  CornerRadiosity corners = flat_corners(radiosity);
  if (rule == VertexColourRule::patch_own || mesh.receiver_patches == 0) return corners;
  const auto receivers = static_cast<std::ptrdiff_t>(mesh.receiver_patches);
  const std::vector<Patch> faces(mesh.radiosity.patches.begin(), mesh.radiosity.patches.begin() + receivers);
  const std::vector<Color> face_b(radiosity.begin(), radiosity.begin() + receivers);
  const std::vector<std::vector<Color>> smooth = corner_radiosity(share_vertices(faces), face_b, rule);
  for (std::size_t f = 0; f < smooth.size(); ++f)
    for (std::size_t k = 0; k < smooth[f].size() && k < 4; ++k) corners[f][k] = smooth[f][k];
  return corners;
}

Color radiosity_at(const TwoPassMesh& mesh, const CornerRadiosity& corners, std::uint32_t primitive,
                   const Point3& x) {
  const int s = mesh.surface_of_primitive.at(primitive);
  require(s >= 0, "radiosity_at: the primitive is not a meshed surface");
  const RadiositySurface& surface = mesh.radiosity.surfaces[static_cast<std::size_t>(s)];
  const auto [n, m] = mesh.grid[static_cast<std::size_t>(s)];
  const PatchCell cell =
      locate_patch(surface_coordinates(surface.polygon, x), n, m, static_cast<int>(surface.polygon.size()));
  const std::array<Color, 4>& c = corners[located_patch(surface, cell, n, m)];
  Color b(0.0);
  for (int k = 0; k < cell.corners; ++k)
    b += cell.weight[static_cast<std::size_t>(k)] * c[static_cast<std::size_t>(k)];
  return b;
}

Emitters::Emitters(const Scene& scene) {
  for (const AreaLight& l : scene.area_lights) {
    patches.push_back(make_patch(l.polygon, Color(0.0), l.emission, 1e-6));
    total += patches.back().area * (l.emission.r + l.emission.g + l.emission.b);
    cumulative.push_back(total);
  }
}

std::size_t Emitters::choose(double u) const {
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u * total);
  return std::min(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
}

Point3 uniform_point_on(const Patch& patch, Rng& rng) {
  // A triangle of the fan from vertex 0, chosen by area; then a uniform point in it.
  const auto& v = patch.vertices;
  const double pick = rng.uniform() * patch.area;
  double acc = 0;
  std::size_t f = 1;
  for (; f + 2 < v.size(); ++f) {
    acc += 0.5 * length(cross(v[f] - v[0], v[f + 1] - v[0]));
    if (pick < acc) break;
  }
  double s = rng.uniform(), r = rng.uniform();
  if (s + r > 1) s = 1 - s, r = 1 - r;
  return v[0] + s * (v[f] - v[0]) + r * (v[f + 1] - v[0]);
}

Vec3 cosine_direction(const Vec3& normal, Rng& rng) {
  // Malley's method: a uniform point on the unit disc lifted to the hemisphere.
  const double r2 = rng.uniform(), phi = 2 * pi * rng.uniform(), r = std::sqrt(r2);
  return Frame::around(normal).to_world(r * std::cos(phi), r * std::sin(phi), std::sqrt(1 - r2));
}

CausticPass caustic_pass(const Scene& scene, const TwoPassMesh& mesh, std::uint64_t photons,
                         std::uint64_t seed, int max_bounces) {
  Stopwatch watch;
  CausticPass pass;
  const std::size_t n = mesh.radiosity.patches.size();
  pass.extra_emission.assign(n, Color(0.0));
  const Emitters emitters(scene);
  if (emitters.patches.empty() || photons == 0 || !(emitters.total > 0)) return pass;
  constexpr std::uint64_t block = 4096;  // photons per random stream: the result does not depend on threads
  const auto blocks = static_cast<std::int64_t>((photons + block - 1) / block);
  // Each block keeps its deposits in order; they are added up block by block afterwards, so
  // the sums (and the image) are the same bit for bit whatever the number of threads.
  std::vector<std::vector<std::pair<std::size_t, Color>>> deposits(static_cast<std::size_t>(blocks));
  std::vector<std::uint64_t> first(static_cast<std::size_t>(blocks), 0);
  ExceptionCollector errors;  // the scene's intersections may be students' code: a throw reaches the caller
#pragma omp parallel for schedule(dynamic)
  for (std::int64_t b = 0; b < blocks; ++b)
    errors.run([&] {
      const auto t = static_cast<std::size_t>(b);
      Rng rng(seed, static_cast<std::uint64_t>(b));
      const std::uint64_t end = std::min<std::uint64_t>(photons, static_cast<std::uint64_t>(b + 1) * block);
      for (std::uint64_t k = static_cast<std::uint64_t>(b) * block; k < end; ++k) {
        const Patch& light = emitters.patches[emitters.choose(rng.uniform())];
        const Point3 origin = uniform_point_on(light, rng);
        Ray ray(origin + 1e-9 * (1.0 + length(origin)) * light.normal, cosine_direction(light.normal, rng));
        // Emitter e is chosen with probability p_e = ΣE_e A_e / total, so the photon carries
        // Φ_e / (N p_e) = E_e · total / (N ΣE_e) per channel.
        const Color& e = light.emission;
        Color power = e * (emitters.total / ((e.r + e.g + e.b) * static_cast<double>(photons)));
        bool specular_path = false;
        for (int bounce = 0; bounce <= max_bounces; ++bounce) {
          const std::optional<SurfaceHit> hit = scene.intersect(ray);
          if (!hit) break;
          const Material& m = scene.materials[hit->material];
          if (!is_specular(m)) {
            const int s = mesh.surface_of_primitive[hit->primitive];
            if (specular_path && s >= 0) {
              const RadiositySurface& surface = mesh.radiosity.surfaces[static_cast<std::size_t>(s)];
              const auto [gn, gm] = mesh.grid[static_cast<std::size_t>(s)];
              const PatchCell cell = locate_patch(surface_coordinates(surface.polygon, hit->point), gn, gm,
                                                  static_cast<int>(surface.polygon.size()));
              const std::size_t j = located_patch(surface, cell, gn, gm);
              const Patch& patch = mesh.radiosity.patches[j];
              deposits[t].emplace_back(j, patch.reflectance * power / patch.area);
            }
            break;
          }
          if (bounce == 0) ++first[t];
          specular_path = true;
          Color k_r = m.reflectance;
          const Color k_t = m.transmittance;
          Vec3 transmitted(0.0);
          const double eta = hit->front_face ? 1.0 / m.index_of_refraction : m.index_of_refraction;
          const Refraction refraction = refract(ray.direction, hit->shading_normal, eta);
          if (refraction.total_internal_reflection)
            k_r += k_t;
          else
            transmitted = refraction.direction;
          const double p_r = mean(k_r), p_t = refraction.total_internal_reflection ? 0.0 : mean(k_t);
          const double u = rng.uniform();
          if (u < p_r) {
            power *= k_r / p_r;
            ray = spawn_ray(*hit, reflect(ray.direction, hit->shading_normal));
          } else if (u < p_r + p_t) {
            power *= k_t / p_t;
            ray = spawn_ray(*hit, transmitted);
          } else {
            break;  // absorbed
          }
        }
      }
    });
  errors.rethrow_if_any();
  for (std::size_t t = 0; t < deposits.size(); ++t) {
    for (const auto& [j, e] : deposits[t]) pass.extra_emission[j] += e;
    pass.specular_first += first[t];
    pass.deposited += deposits[t].size();
  }
  pass.photons = photons;
  pass.seconds = watch.seconds();
  return pass;
}

namespace {

struct EyeTracer {
  const Scene& scene;
  const TwoPassMesh& mesh;
  const CornerRadiosity* corners;
  const TwoPassPlan& plan;
  Tracer tracer;  // lesson 06's, for the local model and shadow rays
};

// The diffuse part D of eq. 13.2 at a hit.
Color diffuse_part(const EyeTracer& e, const SurfaceHit& hit, const Vec3& to_viewer) {
  const bool meshed = e.corners && e.mesh.surface_of_primitive[hit.primitive] >= 0;
  if (!meshed) return own_intensity(e.tracer, hit, to_viewer);
  Color d = radiosity_at(e.mesh, *e.corners, hit.primitive, hit.point);
  if (!e.plan.shadow_rays) return d;
  // Point lights are not in B: the local model adds them (B already holds the emitters' light).
  const Material& m = e.scene.materials[hit.material];
  for (std::size_t l = 0; l < e.scene.point_lights.size(); ++l) {
    const LightSample light = light_sample(e.scene, l, hit.point);
    const Vec3 to_light = normalize(light.position - hit.point);
    if (!(dot(hit.shading_normal, to_light) > 0.0)) continue;
    d += light.intensity *
         phong_term(hit.shading_normal, to_light, to_viewer, m.diffuse, m.specular, m.phong_exponent) *
         shadow_transmission(e.tracer, hit, light.position);
  }
  return d;
}

Color eye_radiance(const EyeTracer& e, const Ray& ray, int depth, RayKind kind) {
  e.tracer.stats->rays.count(kind);
  const std::optional<SurfaceHit> hit = e.scene.intersect(ray, &e.tracer.stats->work);
  if (!hit) return Color(0.0);
  const Material& m = e.scene.materials[hit->material];
  const Color d = diffuse_part(e, *hit, -ray.direction);
  if (depth >= e.plan.max_depth) return d;
  Color k_r = e.plan.reflection ? m.reflectance : Color(0.0);
  Color k_t = e.plan.refraction ? m.transmittance : Color(0.0);
  Color reflected(0.0), transmitted(0.0);
  if (max_channel(k_t) > 0.0) {
    const double eta = hit->front_face ? 1.0 / m.index_of_refraction : m.index_of_refraction;
    const Refraction t = refract(ray.direction, hit->shading_normal, eta);
    if (t.total_internal_reflection) {
      k_r += k_t;  // no transmitted ray: its energy is reflected
      k_t = Color(0.0);
    } else {
      transmitted = eye_radiance(e, spawn_ray(*hit, t.direction), depth + 1, RayKind::refraction);
    }
  }
  if (max_channel(k_r) > 0.0)
    reflected = eye_radiance(e, spawn_ray(*hit, reflect(ray.direction, hit->shading_normal)), depth + 1,
                             RayKind::reflection);
  return second_pass_radiance(d, k_r, reflected, k_t, transmitted);
}

}  // namespace

EyePass eye_pass(const Scene& scene, const TwoPassMesh& mesh, const CornerRadiosity* corners,
                 const TwoPassPlan& plan, int width, int height) {
  Stopwatch watch;
  const EffectsPlan local{.reflection = plan.reflection,
                          .refraction = plan.refraction,
                          .shadows = plan.shadow_rays,
                          .shadow_attenuation = plan.shadow_rays && plan.refraction,
                          .max_depth = plan.max_depth,
                          .skip_zero_weights = true,
                          .analysed = true};
  const PinholeCamera camera =
      render_camera(scene, RenderSettings{.width = width, .height = height, .max_depth = plan.max_depth});
  EyePass pass;
  pass.image = Image(camera.width(), camera.height());
  std::vector<TraceStats> rows(static_cast<std::size_t>(camera.height()));
  parallel_rows(camera.height(), [&](int y) {  // a throw of the students' shading reaches the caller
    TraceStats& stats = rows[static_cast<std::size_t>(y)];
    const EyeTracer e{scene, mesh, corners, plan, Tracer{scene, local, Color(0.0), &stats, nullptr}};
    for (int x = 0; x < camera.width(); ++x)
      pass.image.at(x, y) = eye_radiance(e, camera.pixel_ray(x, y), 0, RayKind::primary);
  });
  for (const TraceStats& s : rows) pass.stats += s;
  pass.seconds = watch.seconds();
  return pass;
}

}  // namespace illum
