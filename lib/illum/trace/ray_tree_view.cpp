#include "illum/trace/ray_tree_view.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "illum/core/error.hpp"
#include "illum/trace/contribution_cutoff.hpp"

namespace illum {

const char* to_string(BranchFate fate) {
  switch (fate) {
    case BranchFate::cast:
      return "cast";
    case BranchFate::depth_limit:
      return "depth_limit";
    case BranchFate::total_internal_reflection:
      return "total_internal_reflection";
    case BranchFate::pruned:
      return "pruned";
    case BranchFate::zero_factor:
      return "zero_factor";
    case BranchFate::switched_off:
      return "switched_off";
    case BranchFate::not_cast:
      return "not_cast";
  }
  return "?";
}

const char* to_string(StopReason reason) {
  switch (reason) {
    case StopReason::continues:
      return "continues";
    case StopReason::missed:
      return "missed";
    case StopReason::depth_limit:
      return "depth_limit";
    case StopReason::pruned:
      return "pruned";
    case StopReason::no_secondary:
      return "no_secondary";
    case StopReason::not_cast:
      return "not_cast";
    case StopReason::reached_light:
      return "reached_light";
    case StopReason::blocked:
      return "blocked";
  }
  return "?";
}

namespace {

ShadowSegment segment_of(const Scene& scene, const RayTreeNode& n) {
  ShadowSegment s{.origin = n.origin, .transmission = n.local};
  if (n.hit) {
    s.crossed = true, s.primitive = n.primitive, s.material = n.material, s.t = n.t, s.end = n.point;
    s.front_face = n.front_face;
    return s;
  }
  s.end = n.point, s.t = n.range.hi;
  if (is_black(n.local)) {
    // An opaque plan asks Scene::occluded, which says whether something
    // blocks but records nothing: find the nearest surface again, to show
    // where the ray stops rather than drawing it on to the light.
    if (const auto blocker = scene.intersect(Ray(n.origin, n.direction, n.range))) {
      s.crossed = true, s.primitive = blocker->primitive, s.material = blocker->material;
      s.t = blocker->t, s.end = blocker->point, s.front_face = blocker->front_face;
    }
  }
  return s;
}

// The branches of a surface hit, as evaluate's contract (ray_tree.hpp) decides them.
std::vector<RayTreeBranch> branches_of(const Scene& scene, const PixelTree& pixel, const RayTreeView& view,
                                       const RayTreeViewNode& v, const RayTreeNode& n) {
  const Material& m = scene.materials[n.material];
  const EffectsPlan& plan = pixel.plan;
  const bool skip = plan.skip_zero_weights;
  const auto child_of_kind = [&](RayKind kind) {
    for (int c : v.children)
      if (view.nodes[static_cast<std::size_t>(c)].kind == kind) return c;
    return -1;
  };
  const bool tir = n.total_internal_reflection;
  const Color k_t = m.transmittance;
  const Color k_r = m.reflectance + (tir ? k_t : Color(0.0));
  std::vector<RayTreeBranch> out;
  for (const RayKind kind : {RayKind::refraction, RayKind::reflection}) {
    const bool refraction = kind == RayKind::refraction;
    RayTreeBranch b{.kind = kind, .factor = refraction ? k_t : k_r, .child = child_of_kind(kind)};
    const bool on = refraction ? plan.refraction : plan.reflection;
    if (b.child >= 0)
      b.fate = BranchFate::cast;
    else if (!on)
      b.fate = BranchFate::switched_off;
    else if (skip && is_black(b.factor))
      b.fate = BranchFate::zero_factor;
    else if (n.depth >= plan.max_depth)
      b.fate = BranchFate::depth_limit;
    else if (refraction && tir)
      b.fate = BranchFate::total_internal_reflection;
    else if (pruned(pixel.min_contribution, n.weight * b.factor))
      b.fate = BranchFate::pruned;
    else
      b.fate = BranchFate::not_cast;
    out.push_back(b);
  }
  return out;
}

StopReason stop_of(const RayTreeViewNode& v, const RayTreeNode& first) {
  if (v.kind == RayKind::shadow)
    return is_black(v.segments.back().transmission) ? StopReason::blocked : StopReason::reached_light;
  if (!first.hit) return StopReason::missed;
  const auto any = [&](BranchFate fate) {
    for (const RayTreeBranch& b : v.branches)
      if (b.fate == fate) return true;
    return false;
  };
  // Shadow rays end at their lights: the tree goes on only through a reflected or refracted child.
  if (any(BranchFate::cast)) return StopReason::continues;
  if (any(BranchFate::depth_limit)) return StopReason::depth_limit;
  if (any(BranchFate::not_cast)) return StopReason::not_cast;
  if (any(BranchFate::pruned)) return StopReason::pruned;
  return StopReason::no_secondary;
}

}  // namespace

RayTreeView view_ray_tree(const Scene& scene, const PixelTree& pixel) {
  const std::vector<RayTreeNode>& record = pixel.tree.nodes;
  RayTreeView view;
  std::vector<int> view_of(record.size(), -1);
  // The shadow ray still walking towards (parent, light): the view node whose
  // last segment crossed a surface that lets light through.
  std::map<std::pair<int, std::uint32_t>, int> open_shadow;
  for (std::size_t i = 0; i < record.size(); ++i) {
    const RayTreeNode& n = record[i];
    require(n.parent == no_node || (n.parent >= 0 && static_cast<std::size_t>(n.parent) < i),
            "view_ray_tree: a node's parent must be an earlier node");
    require(!n.hit || n.material < scene.materials.size(),
            "view_ray_tree: a hit's material is not in the scene");
    const int parent = n.parent == no_node ? -1 : view_of[static_cast<std::size_t>(n.parent)];
    if (n.kind == RayKind::shadow && parent >= 0) {
      const auto key = std::make_pair(parent, n.light);
      if (const auto open = open_shadow.find(key); open != open_shadow.end()) {
        RayTreeViewNode& v = view.nodes[static_cast<std::size_t>(open->second)];
        v.rays.push_back(static_cast<int>(i));
        v.segments.push_back(segment_of(scene, n));
        view_of[i] = open->second;
        if (!(v.segments.back().crossed && !is_black(v.segments.back().transmission)))
          open_shadow.erase(open);
        continue;
      }
    }
    const int index = static_cast<int>(view.nodes.size());
    RayTreeViewNode v{.kind = n.kind,
                      .depth = n.depth,
                      .parent = parent,
                      .children = {},
                      .rays = {static_cast<int>(i)},
                      .branches = {},
                      .segments = {}};
    if (n.kind == RayKind::shadow) {
      v.segments.push_back(segment_of(scene, n));
      if (parent >= 0 && v.segments.back().crossed && !is_black(v.segments.back().transmission))
        open_shadow[{parent, n.light}] = index;
    }
    view.nodes.push_back(std::move(v));
    view_of[i] = index;
    if (parent >= 0) view.nodes[static_cast<std::size_t>(parent)].children.push_back(index);
  }
  for (RayTreeViewNode& v : view.nodes) {
    const RayTreeNode& first = record[static_cast<std::size_t>(v.rays.front())];
    if (v.kind != RayKind::shadow && first.hit) v.branches = branches_of(scene, pixel, view, v, first);
    v.stop = stop_of(v, first);
  }
  return view;
}

std::string display_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (std::abs(value) < 1e-6) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", value);
  return buf;
}

std::string display_colour(const Color& c) {
  const std::string r = display_number(c.r), g = display_number(c.g), b = display_number(c.b);
  if (r == g && g == b) return r;
  return "(" + r + ", " + g + ", " + b + ")";
}

std::string primitive_name(const Scene& scene, std::uint32_t primitive, const std::string& unknown) {
  if (primitive == no_primitive || primitive >= scene.primitives.size()) return unknown;
  const std::string& name = scene.primitives[primitive].name;
  return name.empty() ? "primitive " + std::to_string(primitive) : name;
}

std::string material_name(const Scene& scene, std::uint32_t material) {
  return material < scene.materials.size() ? scene.materials[material].name : "?";
}

std::string light_name(const Scene& scene, std::uint32_t light) {
  std::string name;
  if (light < scene.point_lights.size())
    name = scene.point_lights[light].name;
  else if (light != no_light && light - scene.point_lights.size() < scene.area_lights.size())
    name = scene.area_lights[light - scene.point_lights.size()].name;
  return name.empty() ? "light " + std::to_string(light) : name;
}

std::string stop_text(const Scene& scene, const PixelTree& pixel, const RayTreeView& view, int node) {
  require(node >= 0 && static_cast<std::size_t>(node) < view.nodes.size(), "stop_text: no such node");
  const RayTreeViewNode& v = view.nodes[static_cast<std::size_t>(node)];
  const RayTreeNode& first = pixel.tree.nodes[static_cast<std::size_t>(v.rays.front())];
  const auto factor_name = [](RayKind k) { return k == RayKind::refraction ? "k_t" : "k_r"; };
  const auto branch_note = [&](const RayTreeBranch& b) -> std::string {
    const std::string what =
        std::string(to_string(b.kind)) + " (" + factor_name(b.kind) + " = " + display_colour(b.factor) + ")";
    switch (b.fate) {
      case BranchFate::total_internal_reflection:
        return "no refracted ray: total internal reflection, k_t added to k_r";
      case BranchFate::pruned:
        return what + " pruned: its path weight " + display_colour(first.weight * b.factor) +
               " is below the threshold " + display_number(pixel.min_contribution);
      case BranchFate::not_cast:
        return what + " missing: below the depth limit the contract of evaluate casts it (check evaluate)";
      default:
        return "";
    }
  };
  switch (v.stop) {
    case StopReason::missed:
      return "missed every surface: returns the background " + display_colour(first.color);
    case StopReason::depth_limit: {
      std::string s = "depth limit: a hit at depth " + std::to_string(v.depth) + " spawns no children";
      if (pixel.plan.max_depth < pixel.depth_requested)
        s += " (the plan cut the limit asked, " + std::to_string(pixel.depth_requested) + ", to " +
             std::to_string(pixel.plan.max_depth) + ")";
      return s;
    }
    case StopReason::pruned:
    case StopReason::not_cast: {
      std::string s;
      for (const RayTreeBranch& b : v.branches)
        if (const std::string note = branch_note(b); !note.empty()) s += (s.empty() ? "" : "; ") + note;
      return s;
    }
    case StopReason::no_secondary: {
      bool off = true;
      for (const RayTreeBranch& b : v.branches) off = off && b.fate == BranchFate::switched_off;
      if (off) return "the plan casts no reflected or refracted rays in this scene";
      return "k_r = k_t = 0 at this surface (material " + material_name(scene, first.material) +
             "): no reflected or refracted ray";
    }
    case StopReason::reached_light: {
      const ShadowSegment& last = v.segments.back();
      std::string s = "reached " + light_name(scene, first.light);
      if (v.segments.size() > 1)
        s += " through " + std::to_string(v.segments.size() - 1) +
             (v.segments.size() == 2 ? " surface" : " surfaces") + ", transmission " +
             display_colour(last.transmission);
      return s;
    }
    case StopReason::blocked: {
      const ShadowSegment& last = v.segments.back();
      if (!last.crossed) return "blocked on its way to " + light_name(scene, first.light);
      return "blocked by " + primitive_name(scene, last.primitive, "an unknown surface") + " (material " +
             material_name(scene, last.material) + ") on its way to " + light_name(scene, first.light);
    }
    case StopReason::continues: {
      std::string s;
      for (const RayTreeBranch& b : v.branches)
        if (const std::string note = branch_note(b); !note.empty()) s += (s.empty() ? "" : "; ") + note;
      return s;
    }
  }
  return "";
}

}  // namespace illum
