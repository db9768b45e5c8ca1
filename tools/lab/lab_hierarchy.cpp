#include "lab/lab_hierarchy.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>

#include <nlohmann/json.hpp>

#include "illum/core/stopwatch.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/radiosity/hierarchical_solution.hpp"
#include "illum/radiosity/patch_occluders.hpp"
#include "illum/radiosity/radiosity_scene.hpp"

namespace illum::lab {
namespace {

using nlohmann::json;

// Lesson 14's bounds on its knobs (lessons/14_hierarchical_radiosity/options.cpp), and its defaults:
// the demonstration's ε_F, ε_BF and smallest edge.
constexpr double min_epsilon_f = 0.02, max_epsilon_f = 1.0, min_epsilon_bf = 1e-4, max_epsilon_bf = 1e6;
constexpr double max_split_elements = 200000;  // the scene's area over min_edge², as lesson 14 allows
// A solve stops after this much work: the knobs at their finest on the room ask for tens of millions of
// visibility segments, and a request must not hold a core for minutes.
constexpr double solve_seconds = 20;
constexpr int max_sweeps = 1000;               // solve_links' bound, each solve
constexpr std::size_t max_links_shown = 4000;  // of one clicked element and its ancestors
constexpr std::size_t max_solutions = 4;

std::string number_text(double v) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

json corner_list(const Patch& p) {
  json out = json::array();
  for (const Point3& v : p.vertices)
    for (int k = 0; k < 3; ++k) out.push_back(v[k]);
  return out;
}

json colour_json(const Color& c) { return json::array({to_float(c.r), to_float(c.g), to_float(c.b)}); }

}  // namespace

struct HierarchyLab::Solved {
  std::string scene_id;
  RadiosityScene scene;
  HierarchicalSolution solution;
  std::vector<int> leaves;
  std::string leaves_json;  // the part of every answer that does not depend on the clicked element
};

std::string HierarchyLab::hierarchy_json(const Params& params, const Work& work) {
  const Query q(params, {"scene", "epsilon_f", "epsilon_bf", "min_edge", "element"});
  const SceneEntry& entry = find_scene(scenes_, q.name_or("scene", "room"));
  const double epsilon_f = q.number_or("epsilon_f", min_epsilon_f, max_epsilon_f, 0.4);
  const double epsilon_bf = q.number_or("epsilon_bf", min_epsilon_bf, max_epsilon_bf, 0.01);
  const double min_edge = q.number_or("min_edge", 1e-3, 1e6, 150);
  // Read before the solve (a malformed one is refused at once), checked against the elements after it.
  const long long element = q.has("element") ? q.integer("element", 0, std::numeric_limits<int>::max()) : -1;
  const std::string key =
      entry.id + "|" + number_text(epsilon_f) + "|" + number_text(epsilon_bf) + "|" + number_text(min_edge);
  std::shared_ptr<const Solved> s;
  {
    const std::lock_guard lock(mutex_);
    for (auto it = solved_.begin(); it != solved_.end() && !s; ++it)
      if (it->first == key) s = it->second, std::rotate(solved_.begin(), it, it + 1);
  }
  if (!s) {
    auto made = std::make_shared<Solved>();
    made->scene_id = entry.id;
    // Every surface one patch, a root (lesson 14's load_roots).
    made->scene = load_radiosity_scene(entry.source, std::numeric_limits<double>::max());
    const std::vector<Patch>& roots = made->scene.patches;
    double area = 0, emitted = 0;
    for (const Patch& p : roots) area += p.area, emitted += max_channel(p.emission);
    if (!(emitted > 0))
      throw BadRequest("no surface of scene '" + entry.id + "' emits light: nothing to solve");
    if (area / (min_edge * min_edge) > max_split_elements)
      throw BadRequest(q.asked("min_edge") + " lets scene '" + entry.id + "' split into " +
                       std::to_string(static_cast<long long>(area / (min_edge * min_edge))) +
                       " elements; the lab allows " +
                       std::to_string(static_cast<long long>(max_split_elements)));
    const PatchOccluders occluders(roots);  // lesson 08's BVH, for the links' visibility
    Stopwatch watch;
    std::uint64_t asked = 0;
    const SegmentVisible visible = [&](const Point3& a, const Point3& b) {
      if (++asked % 4096 == 0) {
        work.check();
        if (watch.seconds() > solve_seconds)
          throw BadRequest("scene '" + entry.id + "' with epsilon_f=" + number_text(epsilon_f) +
                           ", epsilon_bf=" + number_text(epsilon_bf) + ", min_edge=" + number_text(min_edge) +
                           " took more than " + number_text(solve_seconds) +
                           " s to link: raise epsilon_f, epsilon_bf or min_edge");
      }
      return occluders.mutually_visible(a, b);
    };
    HierarchicalSettings settings;
    settings.refine = {.epsilon_f = epsilon_f, .epsilon_bf = epsilon_bf, .min_area = min_edge * min_edge};
    settings.max_iterations = max_sweeps;
    made->solution = solve_hierarchical(roots, settings, visible);  // lesson 14's exercise unit
    const ElementHierarchy& h = made->solution.hierarchy;
    made->leaves = leaves(h);
    json ids = json::array(), counts = json::array(), vertices = json::array(), normal = json::array(),
         radiosity = json::array(), root = json::array(), emission = json::array();
    for (const int e : made->leaves) {
      const Patch& p = h[e].patch;
      ids.push_back(e), counts.push_back(p.vertices.size()), root.push_back(p.surface);
      for (const Point3& v : p.vertices)
        for (int k = 0; k < 3; ++k) vertices.push_back(v[k]);
      for (int k = 0; k < 3; ++k)
        normal.push_back(p.normal[k]), radiosity.push_back(to_float(h[e].radiosity[k])),
            emission.push_back(p.emission[k]);
    }
    json surfaces = json::array();
    for (const RadiositySurface& surface : made->scene.surfaces) surfaces.push_back(surface.name);
    json camera = nullptr;
    if (const auto& c = made->scene.camera)
      camera = {{"eye", triple(c->eye)},
                {"target", triple(c->target)},
                {"up", triple(c->up)},
                {"vertical_fov_degrees", c->vertical_fov_degrees}};
    const HierarchicalSolution& r = made->solution;
    json out{{"scene", entry.id},
             {"name", made->scene.name},
             {"epsilon_f", epsilon_f},
             {"epsilon_bf", epsilon_bf},
             {"min_edge", min_edge},
             {"roots", h.roots},
             {"elements", h.elements.size()},
             {"links", h.links.size()},
             {"refinement_passes", r.refinement_passes},
             {"sweeps", r.iterations},
             {"converged", r.converged},
             {"segments", r.segments},
             {"seconds", r.seconds},
             {"camera", camera},
             {"surfaces", surfaces},
             {"patches", made->leaves.size()},  // the leaves, in the shape of /api/radiosity/mesh
             {"element", ids},
             {"surface", root},
             {"vertex_counts", counts},
             {"vertices", vertices},
             {"normal", normal},
             {"emission", emission},
             {"radiosity", radiosity}};
    made->leaves_json = out.dump();
    s = made;
    const std::lock_guard lock(mutex_);
    solved_.insert(solved_.begin(), {key, s});
    if (solved_.size() > max_solutions) solved_.pop_back();
  }
  const ElementHierarchy& h = s->solution.hierarchy;
  json selected = nullptr;
  if (element >= 0) {
    if (element >= static_cast<long long>(h.elements.size()))
      throw BadRequest("parameter 'element' = " + std::to_string(element) + " is outside 0 … " +
                       std::to_string(h.elements.size() - 1) + " (this hierarchy's elements)");
    const int e = static_cast<int>(element);
    // The chain from the element up to its root; the links each of them gathers on.
    json chain = json::array();
    std::vector<int> up;
    for (int a = e; a >= 0; a = h[a].parent) up.push_back(a);
    for (const int a : up)
      chain.push_back({{"element", a},
                       {"level", h[a].level},
                       {"area", h[a].patch.area},
                       {"radiosity", colour_json(h[a].radiosity)},
                       {"gathered", colour_json(h[a].gathered)},
                       {"vertices", corner_list(h[a].patch)}});
    json links = json::array();
    std::size_t total = 0;
    for (const Link& l : h.links) {
      if (std::find(up.begin(), up.end(), l.receiver) == up.end()) continue;
      if (++total > max_links_shown) continue;
      const Patch& other = h[l.source].patch;
      links.push_back(
          {{"receiver", l.receiver},
           {"level", h[l.receiver].level},
           {"source", l.source},
           {"source_level", h[l.source].level},
           {"source_surface", s->scene.surfaces[static_cast<std::size_t>(other.surface)].name},
           {"form_factor", l.form_factor},
           {"estimate", form_factor_estimate(h[l.receiver].patch, other)},  // the oracle's disc
           {"brings", colour_json(h[l.receiver].patch.reflectance * h[l.source].radiosity * l.form_factor)},
           {"centroid", triple(other.centroid)},
           {"vertices", corner_list(other)}});
    }
    const Patch& p = h[e].patch;
    selected = {{"element", e},
                {"surface", s->scene.surfaces[static_cast<std::size_t>(p.surface)].name},
                {"leaf", h.is_leaf(e)},
                {"centroid", triple(p.centroid)},
                {"normal", triple(p.normal)},
                {"chain", chain},
                {"links", links},
                {"links_total", total},
                {"links_shown", std::min(total, max_links_shown)}};
  }
  // The leaves' part is kept as text; the selection is added to its closing brace.
  std::string body = s->leaves_json;
  body.pop_back();
  return body + ",\"selected\":" + selected.dump() + "}\n";
}

}  // namespace illum::lab
