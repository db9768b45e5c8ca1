#include "illum/trace/ray_tree_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

namespace illum {

namespace {

nlohmann::json triple(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

std::string primitive_name(const Scene& scene, std::uint32_t p) {
  if (p == no_primitive || p >= scene.primitives.size()) return "?";
  const std::string& name = scene.primitives[p].name;
  return name.empty() ? "primitive " + std::to_string(p) : name;
}

std::string material_name(const Scene& scene, std::uint32_t m) {
  return m < scene.materials.size() ? scene.materials[m].name : "?";
}

nlohmann::json node_json(const Scene& scene, const RayTree& tree, int index) {
  const RayTreeNode& n = tree.nodes[static_cast<std::size_t>(index)];
  nlohmann::json j{{"kind", to_string(n.kind)},  {"depth", n.depth},
                   {"origin", triple(n.origin)}, {"direction", triple(n.direction)},
                   {"local", triple(n.local)},   {"weight", triple(n.weight)},
                   {"color", triple(n.color)}};
  j["hit"] = nullptr;
  if (n.hit)
    j["hit"] = {{"primitive", primitive_name(scene, n.primitive)},
                {"primitive_index", n.primitive},
                {"t", n.t},
                {"point", triple(n.point)},
                {"material", material_name(scene, n.material)},
                {"front_face", n.front_face}};
  if (n.kind == RayKind::shadow) {
    j["light"] = n.light;
    j["light_end"] = triple(n.origin + n.range.hi * n.direction);
  }
  if (n.total_internal_reflection) j["total_internal_reflection"] = true;
  j["children"] = nlohmann::json::array();
  for (int c : n.children) j["children"].push_back(node_json(scene, tree, c));
  return j;
}

std::string short_color(const Color& c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3g, %.3g, %.3g)", c.r, c.g, c.b);
  return buf;
}

std::string dot_escape(const std::string& s) {
  std::string out;
  for (char ch : s) out += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
  return out;
}

}  // namespace

std::string ray_tree_json(const Scene& scene, const PixelTree& pixel) {
  nlohmann::json j{{"scene", scene.name},
                   {"pixel", {pixel.x, pixel.y}},
                   {"color", triple(pixel.color)},
                   {"nodes", pixel.tree.nodes.size()}};
  j["tree"] = pixel.tree.nodes.empty() ? nlohmann::json(nullptr) : node_json(scene, pixel.tree, 0);
  return j.dump(2) + "\n";
}

std::string ray_tree_dot(const Scene& scene, const PixelTree& pixel) {
  std::string s = "digraph ray_tree {\n  graph [rankdir=TB, fontname=\"Helvetica\", label=\"" +
                  dot_escape(scene.name) + ": ray tree of pixel (" + std::to_string(pixel.x) + ", " +
                  std::to_string(pixel.y) + "), colour " + short_color(pixel.color) +
                  "\", labelloc=t];\n  node [shape=box, style=\"rounded,filled\", fontname=\"Helvetica\", "
                  "fontsize=10];\n";
  for (std::size_t i = 0; i < pixel.tree.nodes.size(); ++i) {
    const RayTreeNode& n = pixel.tree.nodes[i];
    std::string label = std::string(to_string(n.kind)) + " (depth " + std::to_string(n.depth) + ")\\n";
    const bool blocked = n.kind == RayKind::shadow && n.local.r + n.local.g + n.local.b <= 0.0;
    if (n.kind == RayKind::shadow) {
      label += "to light " + std::to_string(n.light) + ": " +
               (blocked ? "blocked by " + dot_escape(primitive_name(scene, n.primitive))
                        : "transmission " + short_color(n.local));
    } else if (n.hit) {
      char t[32];
      std::snprintf(t, sizeof t, "%.4g", n.t);
      label += "hit " + dot_escape(primitive_name(scene, n.primitive)) + " at t = " + t + " (" +
               (n.front_face ? "front" : "back") + ")\\nmaterial " +
               dot_escape(material_name(scene, n.material)) + "\\nI_own " + short_color(n.local) +
               "\\ncolour " + short_color(n.color);
      if (n.total_internal_reflection) label += "\\ntotal internal reflection";
    } else {
      label += "miss: background " + short_color(n.color);
    }
    label += "\\nweight " + short_color(n.weight);
    const char* fill = n.kind == RayKind::primary      ? "#e8e8e8"
                       : n.kind == RayKind::reflection ? "#cdeff5"
                       : n.kind == RayKind::refraction ? "#fde0c2"
                       : blocked                       ? "#f6c6c6"
                                                       : "#fbf3c0";
    s += "  n" + std::to_string(i) + " [label=\"" + label + "\", fillcolor=\"" + fill + "\"" +
         (n.kind == RayKind::shadow ? ", style=\"rounded,dashed,filled\"" : "") + "];\n";
    if (n.parent != no_node) {
      const char* edge = n.kind == RayKind::reflection   ? "k_r"
                         : n.kind == RayKind::refraction ? "k_t"
                                                         : "shadow";
      s += "  n" + std::to_string(n.parent) + " -> n" + std::to_string(i) + " [label=\"" + edge + "\"" +
           (n.kind == RayKind::shadow ? ", style=dashed" : "") + "];\n";
    }
  }
  return s + "}\n";
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

}  // namespace

Image ray_tree_overlay(const Image& render, const PinholeCamera& camera, const PixelTree& pixel) {
  Image image = render;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) image.at(x, y) *= 0.55;  // dimmed, so that the rays stand out
  const double far = 1e3 * (1.0 + length(camera.eye()));
  for (const RayTreeNode& n : pixel.tree.nodes) {
    const bool blocked = n.kind == RayKind::shadow && n.local.r + n.local.g + n.local.b <= 0.0;
    const Color colour = n.kind == RayKind::primary      ? Color(1.0)
                         : n.kind == RayKind::reflection ? Color(0.2, 0.9, 1.0)
                         : n.kind == RayKind::refraction ? Color(1.0, 0.55, 0.1)
                         : blocked                       ? Color(1.0, 0.1, 0.1)
                                                         : Color(1.0, 0.95, 0.2);
    const Point3 end = n.hit ? n.point : n.origin + std::min(n.range.hi, far) * n.direction;
    if (const auto s = segment(camera, n.origin, end)) draw_line(image, s->first, s->second, colour);
  }
  const Vec2 centre(pixel.x + 0.5, pixel.y + 0.5);
  for (int k = 0; k < 64; ++k) {  // a ring of radius 6 pixels around the inspected pixel
    const double a = 2.0 * std::numbers::pi * k / 64;
    plot_dot(image, static_cast<int>(centre.x + 6 * std::cos(a)),
             static_cast<int>(centre.y + 6 * std::sin(a)), Color(1.0, 0.2, 0.9));
  }
  return image;
}

}  // namespace illum
