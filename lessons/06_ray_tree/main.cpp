// lesson06: the ray tree.
//
// From the radiation model to backward ray tracing: the transport equation
// checked on a slab, Whitted's scene rendered by the notes' "evaluar (rayo)",
// the effects plan with its ray counts, the ray-tree inspector (JSON,
// Graphviz, overlay), the offset study, forward tracing shown intractable,
// the depth study and the share of time spent in intersection tests.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/geometry/sphere.hpp"
#include "illum/io/cli_checks.hpp"
#include "illum/io/embedded_scenes.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/io/ray_tree_files.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/trace/optics.hpp"
#include "illum/trace/participating_medium.hpp"
#include "illum/trace/ray_offset.hpp"
#include "illum/trace/ray_tree.hpp"
#include "illum/trace/ray_tree_export.hpp"
#include "illum/trace/ray_tree_render.hpp"

namespace illum {
namespace {

constexpr int default_depth = 5;

// Runs one section of the lesson and says on stderr how long it took.
template <class F>
auto timed(const char* section, F&& run) {
  Stopwatch watch;
  struct Report {
    const char* section;
    Stopwatch& watch;
    ~Report() {
      std::cerr << "lesson06: " << section << " took " << format_number(watch.seconds(), 3) << " s\n";
    }
  } report{section, watch};
  return run();
}

// --- §1 the radiation model: a slab of constant K_t ---------------------------

void radiation_model(OutputFolder& out, bool quick) {
  const Slab absorbing{.extinction = 0.8, .emission = 0.0, .thickness = 2.5};
  const Slab glowing{.extinction = 0.8, .emission = 0.6, .thickness = 2.5};
  const double incoming = 1.0;
  Table table({"medium", "method", "steps", "marched", "closed_form", "relative_error"});
  for (const auto& [name, slab] : {std::pair{"absorbing", absorbing}, std::pair{"glowing", glowing}})
    for (MarchMethod method : {MarchMethod::euler, MarchMethod::midpoint})
      for (int steps = 1; steps <= (quick ? 64 : 4096); steps *= 4) {
        const double marched = march_through_slab(slab, incoming, steps, method);
        const double exact = slab_closed_form(slab, incoming);
        table.add_row({std::string(name), std::string(to_string(method)), std::int64_t{steps}, marched, exact,
                       std::abs(marched - exact) / exact});
      }
  out.table(
      table, "radiation_slab",
      "A ray through a slab, K_t = 0.8, d = 2.5: marching dI/ds = −K_t I + K_a I_e against the closed "
      "form I₀e^(−K_t d) + (K_a I_e/K_t)(1 − e^(−K_t d)); 'absorbing' has emission and in-scattering off",
      4);
  PlotSpec spec{.title = "Transport along a ray through a slab: marching error",
                .x_label = "steps",
                .y_label = "relative error of I(d)",
                .log_x = true,
                .log_y = true};
  for (const char* medium : {"absorbing", "glowing"})
    for (const char* method : {"euler", "midpoint"})
      spec.curves.push_back({.table = "radiation_slab.csv",
                             .x = "steps",
                             .y = "relative_error",
                             .where = {{"medium", medium}, {"method", method}},
                             .title = std::string(medium) + ", " + method});
  out.plot(spec, "radiation_slab", "Marching the transport equation converges to Beer–Lambert's law");
}

// --- §2 Whitted's scene --------------------------------------------------------

RenderSettings whitted_settings(bool quick, int depth = default_depth) {
  return {.width = quick ? 96 : 0,
          .height = quick ? 72 : 0,
          .max_depth = depth,
          .background = Color(0.35, 0.55, 0.9)};
}

RenderResult render_whitted(OutputFolder& out, const Scene& scene, bool quick) {
  Stopwatch watch;
  RenderResult result = render_ray_tree(scene, whitted_settings(quick));
  const double seconds = watch.seconds();
  out.image(result.image, "whitted",
            "Whitted's scene by the ray tree, depth limit 5: mirror ball, glass ball, checkered floor");
  out.text("whitted_render_log.txt",
           scene.name + ", " + std::to_string(result.image.width()) + " × " +
               std::to_string(result.image.height()) + ", depth limit " + std::to_string(default_depth) +
               "\nrender time " + format_number(seconds, 3) + " s\nrays: " + result.stats.rays.summary() +
               "\nintersection tests: " + std::to_string(result.stats.work.intersection_tests) + "\n" +
               result.plan.summary(),
           "Render time, ray counts and plan of the Whitted image");
  Table table({"scene", "width", "height", "depth_limit", "primary", "shadow", "reflection", "refraction",
               "intersection_tests", "render_seconds"});
  const RayCounts& c = result.stats.rays;
  table.add_row({scene.name, std::int64_t(result.image.width()), std::int64_t(result.image.height()),
                 std::int64_t{default_depth}, std::int64_t(c.primary), std::int64_t(c.shadow),
                 std::int64_t(c.reflection), std::int64_t(c.refraction),
                 std::int64_t(result.stats.work.intersection_tests), seconds});
  out.table(table, "whitted_render", "The Whitted render: size, rays by kind, intersection tests and time",
            4);
  return result;
}

// --- §3 the effects plan ---------------------------------------------------------

// Every shipped scene of the course's format, rendered with and without the plan.
void effects_plan_section(OutputFolder& out, bool quick) {
  Table table({"scene", "plan", "depth_limit", "primary", "shadow", "reflection", "refraction", "total_rays",
               "intersection_tests", "seconds", "max_pixel_difference"});
  std::string printed;
  for (const EmbeddedScene& shipped : embedded_scenes()) {
    const Scene scene = load_scene(std::string(shipped.name));
    const RenderSettings settings{.width = quick ? 32 : 120, .max_depth = default_depth};
    RenderSettings without = settings;
    without.use_plan = false;
    Stopwatch watch;
    const RenderResult planned = render_ray_tree(scene, settings);
    const double planned_seconds = watch.seconds();
    watch.restart();
    const RenderResult full = render_ray_tree(scene, without);
    const double full_seconds = watch.seconds();
    double difference = 0.0;
    for (std::size_t i = 0; i < planned.image.pixels().size(); ++i) {
      const Color d = glm::abs(planned.image.pixels()[i] - full.image.pixels()[i]);
      difference = std::max({difference, d.r, d.g, d.b});
    }
    for (const auto* r : {&full, &planned}) {
      const RayCounts& c = r->stats.rays;
      table.add_row({std::string(shipped.name), std::string(r == &full ? "none" : "plan"),
                     std::int64_t{r->plan.max_depth}, std::int64_t(c.primary), std::int64_t(c.shadow),
                     std::int64_t(c.reflection), std::int64_t(c.refraction), std::int64_t(c.total()),
                     std::int64_t(r->stats.work.intersection_tests),
                     r == &full ? full_seconds : planned_seconds, r == &full ? 0.0 : difference});
    }
    printed += "== " + std::string(shipped.name) + " (" + scene.name + ")\n" + planned.plan.summary() +
               "  rays with the plan:    " + planned.stats.rays.summary() + "\n" +
               "  rays without the plan: " + full.stats.rays.summary() + "\n\n";
  }
  std::cout << printed;
  out.text("effects_plan.txt", printed, "The effects plan of every shipped scene, and its ray counts");
  out.table(table, "effects_plan",
            "Ray counts by kind with and without the effects plan (depth limit 5, 120 pixels wide); "
            "'none' is the notes' algorithm as written, both children at every hit; max_pixel_difference "
            "is the largest change of a pixel channel the plan made",
            4);
}

// --- §4 the ray-tree inspector -------------------------------------------------------

// A pixel on the first glass ball of the scene, off its centre so that the
// rays bend: where the inspector looks unless --pixel says otherwise.
std::array<int, 2> glass_pixel(const Scene& scene, const PinholeCamera& camera) {
  for (const Primitive& p : scene.primitives) {
    const Sphere* ball = std::get_if<Sphere>(&p.shape);
    if (!ball || scene.materials[p.material].transmittance.r <= 0.0) continue;
    const auto centre = project_to_image(camera, ball->center);
    const auto rim = project_to_image(camera, ball->center + ball->radius * Vec3(1, 0, 0));
    if (!centre || !rim) continue;
    const double r = length(*rim - *centre);
    return {std::clamp(static_cast<int>(centre->x - 0.45 * r), 0, camera.width() - 1),
            std::clamp(static_cast<int>(centre->y - 0.35 * r), 0, camera.height() - 1)};
  }
  return {camera.width() / 2, camera.height() / 2};
}

void inspect_pixel(OutputFolder& out, const Scene& scene, const RenderResult& render, bool quick,
                   std::optional<std::array<int, 2>> requested) {
  const RenderSettings settings = whitted_settings(quick);
  const PinholeCamera camera = render_camera(scene, settings);
  const std::array<int, 2> xy = requested ? *requested : glass_pixel(scene, camera);
  const PixelTree pixel = trace_pixel_tree(scene, settings, xy[0], xy[1]);
  write_ray_tree_files(out, scene, pixel, render.image, camera, "ray_tree");
  std::cout << "ray tree of pixel (" << xy[0] << ", " << xy[1] << "): " << pixel.tree.nodes.size()
            << " rays, depth " << pixel.tree.depth() << "; " << pixel.stats.rays.summary() << "\n";
}

// --- §5 leaving the surface: the offset study ----------------------------------------

// pbrt-v4's γ_n for the unit roundoff of T.
template <class T>
T gamma_bound(int n) {
  const T u = std::numeric_limits<T>::epsilon() / T(2);
  return n * u / (T(1) - n * u);
}

enum class Leave { none, fixed_epsilon, bounded_offset };
constexpr double fixed_epsilon = 1e-4;  // a typical hand-tuned t_min

struct OffsetCase {
  const char* name;
  double distance, radius;
};

struct RehitRates {
  double outgoing = 0;  // reflected rays that met their own sphere again
  double inward = 0;    // refracted rays whose first hit was near t = 0 instead of the far side
  double missed = 0;    // refracted rays that found no hit at all: the far side lay below t_min
};

// Rays hit a sphere from outside; from each hit a reflected ray leaves (it
// must never meet the sphere again) and a refracted ray enters (it must meet
// the sphere next at the far side, a chord 2r·cos θ_t away, not at t ≈ 0).
template <class T>
RehitRates rehit_rates(const OffsetCase& c, Leave leave, int count, std::uint64_t seed) {
  using V = glm::vec<3, T>;
  const V centre = V(T(c.distance), T(-0.5 * c.distance), T(0.25 * c.distance));
  const T radius = T(c.radius);
  Rng rng(seed);
  int outgoing = 0, inward = 0, missed = 0, cases = 0;
  for (int k = 0; k < count; ++k) {
    const double z = rng.uniform(-1, 1), phi = 2 * std::numbers::pi * rng.uniform();
    const V n(T(std::sqrt(1 - z * z) * std::cos(phi)), T(std::sqrt(1 - z * z) * std::sin(phi)), T(z));
    const V jitter(T(rng.uniform(-0.5, 0.5)), T(rng.uniform(-0.5, 0.5)), T(rng.uniform(-0.5, 0.5)));
    const V origin = centre + T(4) * radius * glm::normalize(n + jitter);
    const V dir = glm::normalize(centre + radius * n - origin);
    const auto roots = sphere_roots_stable(origin, dir, centre, radius);
    if (roots.count == 0 || roots.s_near <= T(0)) continue;
    V p = origin + roots.s_near * dir;
    p = centre + (p - centre) * (radius / glm::length(p - centre));  // re-projected, as the tracer does
    const V error = gamma_bound<T>(5) * (glm::abs(p - centre) + glm::abs(centre));
    const V normal = glm::normalize(p - centre);  // outward; the ray arrives against it
    const V mirror = dir - T(2) * glm::dot(normal, dir) * normal;
    const V into = glm::normalize(V(refract(Vec3(dir), Vec3(normal), 1.0 / 1.5).direction));
    ++cases;
    for (int pass = 0; pass < 2; ++pass) {
      const V w = pass == 0 ? mirror : into;
      const V start = leave == Leave::bounded_offset ? offset_ray_origin(p, error, normal, w) : p;
      const T t_min = leave == Leave::fixed_epsilon ? T(fixed_epsilon) : T(0);
      const auto again = sphere_roots_stable(start, w, centre, radius);
      T first = std::numeric_limits<T>::infinity();  // the nearest root in range
      if (again.count > 0 && again.s_far > t_min) first = again.s_near > t_min ? again.s_near : again.s_far;
      const T chord = T(2) * glm::dot(-normal, w) * radius;
      if (pass == 0)
        outgoing += std::isfinite(first) ? 1 : 0;
      else if (!std::isfinite(first))
        ++missed;
      else
        inward += first < T(0.5) * chord ? 1 : 0;
    }
  }
  const double n = std::max(cases, 1);
  return {outgoing / n, inward / n, missed / n};
}

void offset_study(OutputFolder& out, bool quick, std::uint64_t seed) {
  const int count = quick ? 2000 : 100000;
  Table table({"precision", "sphere", "distance", "radius", "leave", "outgoing_rehit_rate",
               "inward_rehit_rate", "inward_missed_rate", "distance_plotted"});
  const std::pair<Leave, const char*> methods[] = {{Leave::none, "none (t > 0)"},
                                                   {Leave::fixed_epsilon, "fixed epsilon 1e-4"},
                                                   {Leave::bounded_offset, "bounded offset"}};
  const OffsetCase cases[] = {{"at the origin", 0.0, 1.0},
                              {"at 10^2", 1e2, 1.0},
                              {"at 10^4", 1e4, 1.0},
                              {"small (r = 10^-5) at the origin", 0.0, 1e-5}};
  for (const char* precision : {"float", "double"})
    for (const OffsetCase& c : cases)
      for (const auto& [leave, name] : methods) {
        const RehitRates r = precision[0] == 'f' ? rehit_rates<float>(c, leave, count, seed)
                                                 : rehit_rates<double>(c, leave, count, seed);
        table.add_row({std::string(precision), std::string(c.name), c.distance, c.radius, std::string(name),
                       r.outgoing, r.inward, r.missed, std::max(1.0, c.distance)});
      }
  out.table(table, "offset_study",
            "Secondary rays leaving a sphere, by how they leave: reflected rays that hit their own sphere "
            "again, refracted rays that hit it near t = 0, refracted rays that miss its far side",
            3);
  PlotSpec spec{.title = "Reflected rays that hit their own unit sphere again",
                .x_label = "distance of the sphere from the origin (0 plotted at 1)",
                .y_label = "re-hit rate",
                .log_x = true};
  for (const char* precision : {"float", "double"})
    for (const auto& [leave, name] : methods)
      spec.curves.push_back({.table = "offset_study.csv",
                             .x = "distance_plotted",
                             .y = "outgoing_rehit_rate",
                             .where = {{"precision", precision}, {"leave", name}, {"radius", 1.0}},
                             .title = std::string(name) + ", " + precision});
  out.plot(spec, "offset_study", "Re-hit rate of reflected rays: fixed epsilon against the bounded offset");
}

// --- §6 forward tracing is intractable ----------------------------------------------

// The eye's pupil for forward tracing: a disc at the camera's eye, facing the
// view. A human pupil's radius is 1–4 mm (the scene's units are metres); a
// camera lens of 10 cm radius is generous.
constexpr double pupil_radii[2] = {0.004, 0.1};

struct ForwardCount {
  std::uint64_t reached[2] = {0, 0};  // photons that entered each pupil inside the field of view
  std::vector<char> pixel_hit[2];
};

// Photons leave the first point light in uniform directions and are followed
// through up to four surfaces: a diffuse surface scatters them in a cosine-
// distributed direction, a mirror reflects them, glass refracts them (or
// reflects them totally). After each bounce, a photon whose path crosses the
// pupil unobstructed reaches the eye, in the pixel its direction falls in.
void trace_photons(const Scene& scene, const PinholeCamera& camera, std::uint64_t first, std::uint64_t count,
                   std::uint64_t seed, ForwardCount& result) {
  const Point3 eye = camera.eye();
  const Vec3 view = camera.ray_through(0.5 * camera.width(), 0.5 * camera.height()).direction;
  const Point3 source = scene.point_lights.at(0).position;
  for (std::uint64_t k = first; k < first + count; ++k) {
    Rng rng(seed ^ (0x9e3779b97f4a7c15ULL * (k + 1)));
    const double z = rng.uniform(-1, 1), phi = 2 * std::numbers::pi * rng.uniform();
    Ray ray(source, Vec3(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z));
    for (int bounce = 0; bounce < 4; ++bounce) {
      const auto hit = scene.intersect(ray);
      if (!hit) break;
      const Material& m = scene.materials[hit->material];
      Vec3 next;
      if (m.transmittance.r > 0.0) {
        const Refraction t = refract(ray.direction, hit->shading_normal,
                                     hit->front_face ? 1.0 / m.index_of_refraction : m.index_of_refraction);
        next = t.total_internal_reflection ? reflect(ray.direction, hit->shading_normal) : t.direction;
      } else if (m.reflectance.r > 0.5) {
        next = reflect(ray.direction, hit->shading_normal);
      } else {  // cosine-distributed about the normal (Malley's method)
        const double r = std::sqrt(rng.uniform()), a = 2 * std::numbers::pi * rng.uniform();
        const Vec3 n = hit->shading_normal;
        const Vec3 u = normalize(cross(std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0), n));
        next = normalize(r * std::cos(a) * u + r * std::sin(a) * cross(n, u) + std::sqrt(1 - r * r) * n);
      }
      ray = spawn_ray(*hit, next);
      // Does the new path cross the pupil disc (plane through the eye, normal `view`)?
      const double facing = dot(ray.direction, view);
      if (facing < 0.0) {
        const double s = dot(eye - ray.origin, view) / facing;
        const double miss_distance = s > 0.0 ? length(ray.at(s) - eye) : infinity;
        const auto pixel = project_to_image(camera, eye - ray.direction);
        if (miss_distance <= pupil_radii[1] && pixel && pixel->x >= 0 && pixel->y >= 0 &&
            pixel->x < camera.width() && pixel->y < camera.height() &&
            !scene.occluded(Ray(ray.origin, ray.direction, Interval(0.0, s)))) {
          const auto index =
              static_cast<std::size_t>(pixel->y) * camera.width() + static_cast<std::size_t>(pixel->x);
          for (int p = 0; p < 2; ++p)
            if (miss_distance <= pupil_radii[p]) ++result.reached[p], result.pixel_hit[p][index] = 1;
        }
      }
    }
  }
}

ForwardCount empty_count(std::size_t pixels) {
  ForwardCount c;
  for (auto& hit : c.pixel_hit) hit.assign(pixels, 0);
  return c;
}

void forward_tracing(OutputFolder& out, const Scene& scene, bool quick, std::uint64_t seed,
                     std::uint64_t most) {
  const PinholeCamera camera = render_camera(scene, whitted_settings(quick));
  const std::size_t pixels = static_cast<std::size_t>(camera.width()) * camera.height();
  Table table({"method", "pupil_radius", "rays_shot", "rays_reaching_the_eye", "pixels_reached",
               "share_of_pixels", "rays_shot_per_pixel_reached"});
  ForwardCount total = empty_count(pixels);
  std::uint64_t shot = 0;
  for (std::uint64_t n = 1000; n <= (quick ? 10000 : most); n *= 10) {
    const std::uint64_t extra = n - shot;  // the photons shot so far are kept: each row extends the last
    constexpr int chunks = 32;
    std::vector<ForwardCount> parts(chunks, empty_count(pixels));
#pragma omp parallel for schedule(dynamic, 1)
    for (int c = 0; c < chunks; ++c)
      trace_photons(scene, camera, shot + extra * c / chunks, extra * (c + 1) / chunks - extra * c / chunks,
                    seed, parts[static_cast<std::size_t>(c)]);
    shot = n;
    for (int p = 0; p < 2; ++p) {
      for (const ForwardCount& part : parts) {
        total.reached[p] += part.reached[p];
        for (std::size_t i = 0; i < pixels; ++i) total.pixel_hit[p][i] |= part.pixel_hit[p][i];
      }
      const auto reached = std::count(total.pixel_hit[p].begin(), total.pixel_hit[p].end(), 1);
      table.add_row({std::string("forward from the light"), pupil_radii[p], std::int64_t(n),
                     std::int64_t(total.reached[p]), std::int64_t(reached), 1.0 * reached / pixels,
                     reached ? 1.0 * n / reached : infinity});
    }
    report_progress("lesson06", "forward tracing", static_cast<int>(std::log10(n)) - 2,
                    static_cast<int>(std::log10(quick ? 10000 : most)) - 2);
  }
  table.add_row({std::string("backward from the eye"), 0.0, std::int64_t(pixels), std::int64_t(pixels),
                 std::int64_t(pixels), 1.0, 1.0});
  out.table(
      table, "forward_tracing",
      "Forward tracing: photons shot from the light, followed through four bounces, that enter a pupil at "
      "the eye (radius 4 mm or 10 cm), against the backward tracer's one primary ray per pixel",
      3);
  PlotSpec spec{.title = "Forward tracing: pixels reached as photons are shot",
                .x_label = "photons shot from the light",
                .y_label = "share of the image's pixels reached",
                .log_x = true};
  for (const double r : pupil_radii)
    spec.curves.push_back({.table = "forward_tracing.csv",
                           .x = "rays_shot",
                           .y = "share_of_pixels",
                           .where = {{"method", "forward from the light"}, {"pupil_radius", r}},
                           .title = "pupil radius " + format_number(r, 2) + " m"});
  out.plot(spec, "forward_tracing", "Share of pixels a forward tracer reaches with N photons");
}

// --- §7 the depth study ---------------------------------------------------------------

double rms_difference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) sum += length_squared(a.pixels()[i] - b.pixels()[i]);
  return std::sqrt(sum / (3.0 * static_cast<double>(a.pixels().size())));
}

void depth_study(OutputFolder& out, const Scene& scene, bool quick) {
  RenderSettings settings{.width = quick ? 32 : 120, .background = whitted_settings(quick).background};
  settings.max_depth = 16;
  const Image reference = render_ray_tree(scene, settings).image;
  Table table({"depth_limit", "rms_error", "max_error", "rays", "rays_per_pixel", "tree_nodes_per_pixel",
               "tree_nodes_per_pixel_no_plan", "worst_case_nodes", "seconds"});
  for (int depth = 0; depth <= 10; ++depth) {
    settings.max_depth = depth, settings.use_plan = true;
    Stopwatch watch;
    const RenderResult r = render_ray_tree(scene, settings);
    const double seconds = watch.seconds();
    settings.use_plan = false;
    const RenderResult literal = render_ray_tree(scene, settings);
    double worst = 0.0;
    for (std::size_t i = 0; i < r.image.pixels().size(); ++i) {
      const Color d = glm::abs(r.image.pixels()[i] - reference.pixels()[i]);
      worst = std::max({worst, d.r, d.g, d.b});
    }
    const double pixels = static_cast<double>(r.image.pixels().size());
    const auto tree_nodes = [&](const RayCounts& c) {
      return (c.primary + c.reflection + c.refraction) / pixels;
    };
    table.add_row({std::int64_t{depth}, rms_difference(r.image, reference), worst,
                   std::int64_t(r.stats.rays.total()), r.stats.rays.total() / pixels,
                   tree_nodes(r.stats.rays), tree_nodes(literal.stats.rays), std::pow(2.0, depth + 1) - 1.0,
                   seconds});
    report_progress("lesson06", "depth study", depth + 1, 11);
  }
  out.table(
      table, "depth_study",
      "Depth limit 0…10 against a depth-16 reference (Whitted, 120 × 90): image error, rays, time, and "
      "the tree's size per pixel (primary + secondary rays) with the plan, without it, and the worst case "
      "2^(d+1) − 1",
      3);
  PlotSpec error{.title = "Ray tree: image error against depth 16",
                 .x_label = "depth limit",
                 .y_label = "error (linear RGB)",
                 .log_y = true,
                 .key = PlotKey::inside_top_right};  // shown small, two side by side
  for (const auto& [column, title] :
       {std::pair{"rms_error", "RMS error"}, std::pair{"max_error", "max error"}})
    error.curves.push_back(
        {.table = "depth_study.csv", .x = "depth_limit", .y = column, .y_positive = true, .title = title});
  out.plot(error, "depth_error", "Image error against the depth-16 reference, by depth limit");
  PlotSpec size{.title = "Ray tree: size per pixel",
                .x_label = "depth limit",
                .y_label = "rays of the tree per pixel",
                .log_y = true,
                .key = PlotKey::inside_top_left};  // shown small, two side by side
  for (const auto& [column, title] :
       {std::pair{"tree_nodes_per_pixel", "with the effects plan"},
        std::pair{"tree_nodes_per_pixel_no_plan", "notes' algorithm, both children always"},
        std::pair{"worst_case_nodes", "worst case 2^{d+1} - 1"}})
    size.curves.push_back({.table = "depth_study.csv", .x = "depth_limit", .y = column, .title = title});
  out.plot(size, "depth_tree_size", "The tree's actual size against the full binary tree");
}

// --- §8 where the time goes: intersection tests -------------------------------------

// Renders serially, recording every ray of every pixel's tree; then casts the
// same rays again through the scene's intersection routines alone. The ratio
// of the two times is the share of the render spent finding intersections.
void intersection_share(OutputFolder& out, const Scene& scene, bool quick) {
  const RenderSettings settings{.width = quick ? 32 : 160,
                                .max_depth = default_depth,
                                .background = whitted_settings(quick).background};
  const PinholeCamera camera = render_camera(scene, settings);
  const EffectsPlan plan = render_plan(scene, settings);
  std::vector<Ray> rays;
  std::vector<char> is_shadow;
  for (int j = 0; j < camera.height(); ++j)
    for (int i = 0; i < camera.width(); ++i)
      for (const RayTreeNode& n : trace_pixel_tree(scene, settings, i, j).tree.nodes) {
        rays.emplace_back(n.origin, n.direction, n.range);
        is_shadow.push_back(n.kind == RayKind::shadow ? 1 : 0);
      }
  double render_seconds = infinity, intersect_seconds = infinity;
  WorkCounters work;
  for (int run = 0; run < 5; ++run) {  // best of five, each serial
    TraceStats stats;
    const Tracer tracer{.scene = scene, .plan = plan, .background = settings.background, .stats = &stats};
    Stopwatch watch;
    for (int j = 0; j < camera.height(); ++j)
      for (int i = 0; i < camera.width(); ++i) do_not_optimize(evaluate(tracer, camera.pixel_ray(i, j)));
    render_seconds = std::min(render_seconds, watch.seconds());
    work = stats.work;
    watch.restart();
    for (std::size_t k = 0; k < rays.size(); ++k) {
      if (is_shadow[k] && !plan.shadow_attenuation)
        do_not_optimize(scene.occluded(rays[k]));
      else
        do_not_optimize(scene.intersect(rays[k]).has_value());
    }
    intersect_seconds = std::min(intersect_seconds, watch.seconds());
  }
  Table table({"scene", "pixels", "rays", "intersection_tests", "render_seconds", "intersection_seconds",
               "time_share_in_intersection"});
  table.add_row({scene.name, std::int64_t(camera.width()) * camera.height(), std::int64_t(rays.size()),
                 std::int64_t(work.intersection_tests), render_seconds, intersect_seconds,
                 intersect_seconds / render_seconds});
  out.table(table, "intersection_share",
            "Share of the render's time spent in intersection tests (brute force over every primitive, one "
            "thread, best of five): the same rays cast again through the intersection routines alone",
            3);
}

}  // namespace
}  // namespace illum

int main(int argc, char** argv) {
  const illum::ProgramInfo info{
      "lesson06", "Lesson 06: the ray tree",
      "Checks the transport equation on a slab, renders Whitted's scene with the ray tree, prints the "
      "effects "
      "plan and its ray counts, writes a pixel's ray tree (JSON, Graphviz, overlay), and runs the offset, "
      "forward-tracing, depth and intersection-share studies."};
  std::vector<int> pixel;
  double forward_most = 1e6;
  return illum::run_program(
      argc, argv, info,
      [&](CLI::App& app) {
        app.add_option("--pixel", pixel, "Inspect the ray tree of pixel X Y of the Whitted image")
            ->expected(2);
        // --quick stops the study at 1e4 photons: with it, --forward-rays would be ignored.
        illum::exclude_quick(app, {app.add_option("--forward-rays", forward_most,
                                                  "Most photons of the forward-tracing study (default 1e6)")
                                       ->check(illum::number_range(1e3, 1e8))});
      },
      [&](const illum::ProgramOptions& options) {
        using namespace illum;
        const Scene whitted = load_scene("whitted");  // scenes/whitted.json, compiled in
        const PinholeCamera camera = render_camera(whitted, whitted_settings(options.quick));
        std::optional<std::array<int, 2>> requested;
        if (!pixel.empty()) {
          if (pixel[0] < 0 || pixel[1] < 0 || pixel[0] >= camera.width() || pixel[1] >= camera.height())
            throw InputError("command line", "--pixel",
                             std::to_string(pixel[0]) + " " + std::to_string(pixel[1]),
                             "outside the " + std::to_string(camera.width()) + " × " +
                                 std::to_string(camera.height()) + " image");
          requested = std::array<int, 2>{pixel[0], pixel[1]};
        }
        OutputFolder out(options.out, info.id, info.title);
        const bool quick = options.quick;
        timed("§1 radiation model", [&] { radiation_model(out, quick); });
        const RenderResult render =
            timed("§2 Whitted render", [&] { return render_whitted(out, whitted, quick); });
        timed("§3 inspector", [&] { inspect_pixel(out, whitted, render, quick, requested); });
        timed("§4 effects plan", [&] { effects_plan_section(out, quick); });
        timed("§5 offset study", [&] { offset_study(out, quick, options.seed); });
        const auto photons = static_cast<std::uint64_t>(forward_most);
        timed("§6 forward tracing", [&] { forward_tracing(out, whitted, quick, options.seed, photons); });
        timed("§7 depth study", [&] { depth_study(out, whitted, quick); });
        timed("§8 intersection share", [&] { intersection_share(out, whitted, quick); });
        out.finish();
      });
}
