#include "illum/trace/ray_tree_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

#include "illum/trace/bitmap_font.hpp"
#include "illum/trace/ray_tree_view.hpp"

namespace illum {

namespace {

nlohmann::json triple(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

nlohmann::json hit_json(const Scene& scene, std::uint32_t primitive, std::uint32_t material, double t,
                        const Point3& point, bool front_face) {
  return {{"primitive", primitive_name(scene, primitive, "?")},
          {"primitive_index", primitive},
          {"t", t},
          {"point", triple(point)},
          {"material", material_name(scene, material)},
          {"front_face", front_face}};
}

struct JsonWriter {
  const Scene& scene;
  const PixelTree& pixel;
  const RayTreeView& view;

  nlohmann::json node(int index) const {
    const RayTreeViewNode& v = view.nodes[static_cast<std::size_t>(index)];
    const RayTreeNode& n = pixel.tree.nodes[static_cast<std::size_t>(v.rays.front())];
    const RayTreeNode& last = pixel.tree.nodes[static_cast<std::size_t>(v.rays.back())];
    nlohmann::json j{{"id", index},
                     {"kind", to_string(v.kind)},
                     {"depth", v.depth},
                     {"rays", v.rays},
                     {"origin", triple(n.origin)},
                     {"direction", triple(n.direction)},
                     {"local", triple(last.local)},
                     {"weight", triple(n.weight)},
                     {"color", triple(n.color)}};
    j["hit"] = nullptr;
    if (v.kind == RayKind::shadow) {
      const ShadowSegment& end = v.segments.back();
      if (v.stop == StopReason::blocked && end.crossed)
        j["hit"] = hit_json(scene, end.primitive, end.material, end.t, end.end, end.front_face);
      j["light"] = n.light;
      j["light_name"] = light_name(scene, n.light);
      j["light_end"] = triple(last.origin + last.range.hi * last.direction);
      j["transmission"] = triple(end.transmission);
      j["segments"] = nlohmann::json::array();
      for (const ShadowSegment& s : v.segments)
        j["segments"].push_back(
            {{"origin", triple(s.origin)},
             {"end", triple(s.end)},
             {"hit", s.crossed ? hit_json(scene, s.primitive, s.material, s.t, s.end, s.front_face)
                               : nlohmann::json()},
             {"transmission", triple(s.transmission)}});
    } else if (n.hit) {
      j["hit"] = hit_json(scene, n.primitive, n.material, n.t, n.point, n.front_face);
    }
    j["stop"] = {{"reason", to_string(v.stop)}, {"text", stop_text(scene, pixel, view, index)}};
    if (!v.branches.empty()) {
      j["branches"] = nlohmann::json::array();
      for (const RayTreeBranch& b : v.branches)
        j["branches"].push_back(
            {{"kind", to_string(b.kind)}, {"fate", to_string(b.fate)}, {"factor", triple(b.factor)}});
    }
    if (n.total_internal_reflection) j["total_internal_reflection"] = true;
    j["children"] = nlohmann::json::array();
    for (int c : v.children) j["children"].push_back(node(c));
    return j;
  }
};

std::string dot_escape(const std::string& s) {
  std::string out;
  for (char ch : s) out += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
  return out;
}

}  // namespace

std::string ray_tree_json(const Scene& scene, const PixelTree& pixel) {
  const RayTreeView view = view_ray_tree(scene, pixel);
  const RayCounts& rays = pixel.stats.rays;
  nlohmann::json j{{"scene", scene.name},
                   {"pixel", {pixel.x, pixel.y}},
                   {"color", triple(pixel.color)},
                   {"nodes", view.nodes.size()},
                   {"rays", pixel.tree.nodes.size()},
                   {"depth_limit", pixel.plan.max_depth},
                   {"depth_requested", pixel.depth_requested},
                   {"min_contribution", pixel.min_contribution},
                   {"rays_by_kind",
                    {{"primary", rays.primary},
                     {"shadow", rays.shadow},
                     {"reflection", rays.reflection},
                     {"refraction", rays.refraction}}}};
  j["tree"] = view.nodes.empty() ? nlohmann::json(nullptr) : JsonWriter{scene, pixel, view}.node(0);
  return j.dump(2) + "\n";
}

std::string ray_tree_dot(const Scene& scene, const PixelTree& pixel, TreeDetail detail) {
  const RayTreeView view = view_ray_tree(scene, pixel);
  const bool summary = detail == TreeDetail::summary;
  std::string s = "digraph ray_tree {\n  graph [rankdir=TB, fontname=\"Helvetica\", label=\"" +
                  dot_escape(scene.name) + ": ray tree of pixel (" + std::to_string(pixel.x) + ", " +
                  std::to_string(pixel.y) + "), colour " + display_colour(pixel.color) + "\", labelloc=t" +
                  (summary ? ", fontsize=22, nodesep=0.15, ranksep=0.3" : "") +
                  "];\n  node [shape=box, style=\"rounded,filled\", fontname=\"Helvetica\", fontsize=" +
                  (summary ? "20" : "10") + "];\n" + (summary ? "  edge [fontsize=18];\n" : "");
  std::string stubs;
  for (std::size_t i = 0; i < view.nodes.size(); ++i) {
    const RayTreeViewNode& v = view.nodes[i];
    const RayTreeNode& n = pixel.tree.nodes[static_cast<std::size_t>(v.rays.front())];
    const std::string stop = stop_text(scene, pixel, view, static_cast<int>(i));
    std::string label = std::string(to_string(v.kind)) + " (depth " + std::to_string(v.depth) + ")\\n";
    const bool blocked = v.stop == StopReason::blocked;
    if (summary) {
      if (v.kind == RayKind::shadow)
        label += blocked ? dot_escape(stop)
                         : "reached " + dot_escape(light_name(scene, n.light)) +
                               (v.segments.size() > 1 ? " through glass" : "");
      else if (n.hit)
        label += dot_escape(primitive_name(scene, n.primitive, "?")) + " (" +
                 (n.front_face ? "front" : "back") + ")";
      else
        label += "missed: background";
    } else if (v.kind == RayKind::shadow) {
      label += "to " + dot_escape(light_name(scene, n.light));
      for (std::size_t k = 0; k + 1 < v.segments.size(); ++k)
        label += "\\nthrough " + dot_escape(primitive_name(scene, v.segments[k].primitive, "?")) +
                 ": transmission " + display_colour(v.segments[k].transmission);
      label += "\\n" + dot_escape(blocked ? stop
                                          : "reached the light, transmission " +
                                                display_colour(v.segments.back().transmission));
    } else if (n.hit) {
      label += "hit " + dot_escape(primitive_name(scene, n.primitive, "?")) +
               " at t = " + display_number(n.t) + " (" + (n.front_face ? "front" : "back") + ")\\nmaterial " +
               dot_escape(material_name(scene, n.material)) + "\\nI_own " + display_colour(n.local) +
               "\\ncolour " + display_colour(n.color);
      if (v.stop != StopReason::continues && !stop.empty()) label += "\\nstops: " + dot_escape(stop);
    } else {
      label += "missed: background " + display_colour(n.color);
    }
    label += "\\nweight " + display_colour(n.weight);
    const char* fill = v.kind == RayKind::primary      ? "#e8e8e8"
                       : v.kind == RayKind::reflection ? "#cdeff5"
                       : v.kind == RayKind::refraction ? "#fde0c2"
                       : blocked                       ? "#f6c6c6"
                                                       : "#fbf3c0";
    s += "  n" + std::to_string(i) + " [label=\"" + label + "\", fillcolor=\"" + fill + "\"" +
         (v.kind == RayKind::shadow ? ", style=\"rounded,dashed,filled\"" : "") + "];\n";
    if (v.parent >= 0) {
      const char* edge = v.kind == RayKind::reflection   ? "k_r"
                         : v.kind == RayKind::refraction ? "k_t"
                                                         : "shadow";
      s += "  n" + std::to_string(v.parent) + " -> n" + std::to_string(i) + " [label=\"" + edge + "\"" +
           (v.kind == RayKind::shadow ? ", style=dashed" : "") + "];\n";
    }
    // A child the tree lacks for a reason worth seeing gets a stub.
    for (const RayTreeBranch& b : v.branches) {
      const char* why = b.fate == BranchFate::total_internal_reflection ? "total internal reflection"
                        : b.fate == BranchFate::pruned                  ? "pruned"
                        : b.fate == BranchFate::not_cast                ? "missing (check evaluate)"
                                                                        : nullptr;
      if (!why) continue;
      std::string parent = std::to_string(i);
      parent.insert(parent.begin(), 'n');  // (not "n" + …: GCC 12 warns falsely of overlapping copies there)
      const std::string id = parent + "_" + to_string(b.kind);
      stubs += "  " + id + " [label=\"no " + to_string(b.kind) + " ray:\\n" + why +
               "\", shape=plaintext, style=\"\", fontcolor=\"#666666\"];\n  " + parent + " -> " + id +
               " [label=\"" + (b.kind == RayKind::refraction ? "k_t" : "k_r") + "\", style=dotted];\n";
    }
  }
  return s + stubs + "}\n";
}

std::optional<Vec2> project_to_image(const PinholeCamera& camera, const Point3& point) {
  // Invert ray_through: the ray through (x, y) points along forward + x·right + y·down.
  const Ray centre = camera.ray_through(0.5 * camera.width(), 0.5 * camera.height());
  const Ray right = camera.ray_through(0.5 * camera.width() + 1.0, 0.5 * camera.height());
  const Ray down = camera.ray_through(0.5 * camera.width(), 0.5 * camera.height() + 1.0);
  const Vec3 f = centre.direction;
  const Vec3 r = right.direction / dot(right.direction, f) - f;  // one pixel step on the plane at distance 1
  const Vec3 d = down.direction / dot(down.direction, f) - f;
  const Vec3 v = point - camera.eye();
  const double depth = dot(v, f);
  if (!(depth > 1e-9 * length(v))) return std::nullopt;
  const Vec3 on_plane = v / depth - f;
  return Vec2(0.5 * camera.width() + dot(on_plane, r) / dot(r, r),
              0.5 * camera.height() + dot(on_plane, d) / dot(d, d));
}

namespace {

void plot_dot(Image& image, int x, int y, const Color& c) {
  if (x >= 0 && y >= 0 && x < image.width() && y < image.height()) image.at(x, y) = c;
}

// A line of width 2 from a to b (pixel coordinates), clipped to the image.
void draw_line(Image& image, Vec2 a, Vec2 b, const Color& c) {
  const double steps = std::min(8192.0, std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y))) + 1.0);
  for (int k = 0; k <= static_cast<int>(steps); ++k) {
    const Vec2 p = a + (b - a) * (k / steps);
    const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    plot_dot(image, x, y, c), plot_dot(image, x + 1, y, c), plot_dot(image, x, y + 1, c);
  }
}

void draw_circle(Image& image, Vec2 centre, double radius, const Color& c) {
  const int steps = std::max(16, static_cast<int>(8 * radius));
  for (int k = 0; k < steps; ++k) {
    const double a = 2.0 * std::numbers::pi * k / steps;
    plot_dot(image, static_cast<int>(std::floor(centre.x + radius * std::cos(a))),
             static_cast<int>(std::floor(centre.y + radius * std::sin(a))), c);
  }
}

// A ray seen end-on: a circle with a dot when it comes towards the camera,
// with a cross when it goes away (the notation for an arrow's tip and tail).
void draw_end_on(Image& image, Vec2 at, bool towards_camera, const Color& c) {
  draw_circle(image, at, 5.0, c);
  draw_circle(image, at, 4.5, c);
  if (towards_camera) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        plot_dot(image, static_cast<int>(std::floor(at.x)) + dx, static_cast<int>(std::floor(at.y)) + dy, c);
  } else {
    draw_line(image, at + Vec2(-3, -3), at + Vec2(3, 3), c);
    draw_line(image, at + Vec2(-3, 3), at + Vec2(3, -3), c);
  }
}

// The segment's end as seen from the camera, pulled in front of the eye when
// it lies behind it (a ray that turns back towards the camera).
std::optional<std::pair<Vec2, Vec2>> segment(const PinholeCamera& camera, Point3 a, Point3 b) {
  const Vec3 f = camera.ray_through(0.5 * camera.width(), 0.5 * camera.height()).direction;
  const double near = 1e-3, da = dot(a - camera.eye(), f), db = dot(b - camera.eye(), f);
  if (da < near && db < near) return std::nullopt;
  if (da < near) a = a + (b - a) * ((near - da) / (db - da));
  if (db < near) b = b + (a - b) * ((near - db) / (da - db));
  const auto pa = project_to_image(camera, a), pb = project_to_image(camera, b);
  if (!pa || !pb) return std::nullopt;
  return std::make_pair(*pa, *pb);
}

const Color primary_colour(1.0), reflection_colour(0.2, 0.9, 1.0), refraction_colour(1.0, 0.55, 0.1),
    shadow_colour(1.0, 0.95, 0.2), blocked_colour(1.0, 0.1, 0.1), pixel_colour(1.0, 0.2, 0.9);

// Draws one ray piece (nothing when it lies wholly behind the camera).
void draw_piece(Image& image, const PinholeCamera& camera, const Point3& a, const Point3& b, const Color& c) {
  const auto s = segment(camera, a, b);
  if (!s) return;
  // Seen end-on: within 2° of the line of sight through its start (a ray
  // that passes that close to the eye projects to a line flung across the
  // image, or to a dot), or shorter than 4 pixels although long in the scene.
  const double scene_length = length(b - a), distance = length(a - camera.eye());
  if (scene_length > 1e-3 * (distance + scene_length) && distance > 0.0) {
    const double along_sight = dot((b - a) / scene_length, (a - camera.eye()) / distance);
    if (std::abs(along_sight) > std::cos(2.0 * std::numbers::pi / 180.0) ||
        length(s->second - s->first) < 4.0) {
      if (const auto at = project_to_image(camera, a)) draw_end_on(image, *at, along_sight < 0.0, c);
      return;
    }
  }
  draw_line(image, s->first, s->second, c);
}

struct LegendEntry {
  const char* text;
  Color colour;
  int mark;  // 0 a line, 1 end-on towards the camera, 2 end-on away, 3 the pixel's ring
};
const LegendEntry legend[] = {
    {"primary", primary_colour, 0},           {"reflection", reflection_colour, 0},
    {"refraction", refraction_colour, 0},     {"shadow", shadow_colour, 0},
    {"shadow, blocked", blocked_colour, 0},   {"towards the camera", Color(0.85), 1},
    {"away from the camera", Color(0.85), 2}, {"the pixel", pixel_colour, 3}};
constexpr int legend_line = 12, legend_pad = 5, legend_swatch = 18;

int legend_column_width() {
  int width = 0;
  for (const LegendEntry& e : legend) width = std::max(width, text_width(e.text));
  return legend_swatch + 4 + width + 12;
}

// Columns of the legend that fit the image's width (at least one), and the strip's height.
int legend_columns(int image_width) {
  return std::clamp((image_width - 2 * legend_pad) / legend_column_width(), 1,
                    static_cast<int>(std::size(legend)));
}
int legend_height(int image_width) {
  const int columns = legend_columns(image_width);
  const int rows = (static_cast<int>(std::size(legend)) + columns - 1) / columns;
  return 2 * legend_pad + rows * legend_line;
}

// The legend, in the strip of rows from `top` down.
void draw_legend(Image& image, int top) {
  const int columns = legend_columns(image.width());
  const int rows = (static_cast<int>(std::size(legend)) + columns - 1) / columns;
  for (std::size_t k = 0; k < std::size(legend); ++k) {
    const LegendEntry& e = legend[k];
    const int column = static_cast<int>(k) / rows, row = static_cast<int>(k) % rows;
    const int x = legend_pad + column * legend_column_width(), y = top + legend_pad + row * legend_line;
    const Vec2 mid(x + legend_swatch / 2.0, y + 3.5);
    if (e.mark == 0)
      draw_line(image, Vec2(x, y + 3), Vec2(x + legend_swatch - 2, y + 3), e.colour);
    else if (e.mark == 3)
      draw_circle(image, mid, 4.0, e.colour);
    else
      draw_end_on(image, mid, e.mark == 1, e.colour);
    draw_text(image, x + legend_swatch + 4, y, e.text, Color(0.95));
  }
}

}  // namespace

Image ray_tree_overlay(const Image& render, const PinholeCamera& camera, const PixelTree& pixel) {
  // The render dimmed, so that the rays stand out, with a strip below it for the legend.
  Image image(render.width(), render.height() + legend_height(render.width()), Color(0.06));
  for (int y = 0; y < render.height(); ++y)
    for (int x = 0; x < render.width(); ++x) image.at(x, y) = 0.55 * render.at(x, y);
  const double far = 1e3 * (1.0 + length(camera.eye()));
  // No Scene here: the record alone says where each ray went (a blocked
  // shadow ray of an opaque plan is drawn to the light in red).
  for (const RayTreeNode& n : pixel.tree.nodes) {
    const bool blocked = n.kind == RayKind::shadow && is_black(n.local);
    const Color colour = n.kind == RayKind::primary      ? primary_colour
                         : n.kind == RayKind::reflection ? reflection_colour
                         : n.kind == RayKind::refraction ? refraction_colour
                         : blocked                       ? blocked_colour
                                                         : shadow_colour;
    const Point3 end = n.hit ? n.point : n.origin + std::min(n.range.hi, far) * n.direction;
    draw_piece(image, camera, n.origin, end, colour);
  }
  draw_circle(image, Vec2(pixel.x + 0.5, pixel.y + 0.5), 6.0, pixel_colour);
  // The rays may have run into the strip: clear it before the legend.
  for (int y = render.height(); y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) image.at(x, y) = Color(0.06);
  draw_legend(image, render.height());
  return image;
}

}  // namespace illum
