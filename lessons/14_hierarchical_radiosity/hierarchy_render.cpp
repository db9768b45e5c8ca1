#include "hierarchy_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "illum/core/pinhole_camera.hpp"

namespace illum::lesson14 {
namespace {

// The ray parameter of the hit with the convex patch (either side), or infinity.
double hit_patch(const Ray& ray, const Patch& patch) {
  const double facing = dot(patch.normal, ray.direction);
  if (std::abs(facing) < 1e-12) return std::numeric_limits<double>::infinity();
  const double t = dot(patch.normal, patch.vertices[0] - ray.origin) / facing;
  if (!(t > 0)) return std::numeric_limits<double>::infinity();
  return depth_inside(patch, ray.at(t)) >= 0 ? t : std::numeric_limits<double>::infinity();
}

// Pixel coordinates of a point seen through the camera (the inverse of
// PinholeCamera::ray_through), or nothing behind the eye.
struct Projector {
  Point3 eye;
  Vec3 forward, right, up;
  double pixel, width, height;
  bool project(const Point3& p, double& x, double& y) const {
    const Vec3 d = p - eye;
    const double z = dot(d, forward);
    if (!(z > 1e-9)) return false;
    x = 0.5 * width + dot(d, right) / (z * pixel);
    y = 0.5 * height - dot(d, up) / (z * pixel);
    return true;
  }
};

Projector projector(const LeafView& view) {
  const RadiosityCamera& c = view.camera;
  const Vec3 f = normalize(c.target - c.eye), r = normalize(cross(f, c.up)), u = cross(r, f);
  const double half = std::tan(0.5 * c.vertical_fov_degrees * std::numbers::pi / 180.0);
  return {c.eye,
          f,
          r,
          u,
          2 * half / view.height,
          static_cast<double>(view.width),
          static_cast<double>(view.height)};
}

// A line of pixels from a to b (both projected), clipped to the picture.
void draw_segment(Image& image, const Projector& p, const Point3& a, const Point3& b, const Color& colour) {
  double ax = 0, ay = 0, bx = 0, by = 0;
  if (!p.project(a, ax, ay) || !p.project(b, bx, by)) return;
  const int steps =
      static_cast<int>(std::min(4096.0, std::ceil(std::max(std::abs(bx - ax), std::abs(by - ay)))));
  for (int k = 0; k <= steps; ++k) {
    const double t = steps > 0 ? static_cast<double>(k) / steps : 0;
    const int x = static_cast<int>(std::floor(ax + t * (bx - ax))),
              y = static_cast<int>(std::floor(ay + t * (by - ay)));
    if (x >= 0 && y >= 0 && x < image.width() && y < image.height()) image.at(x, y) = colour;
  }
}

}  // namespace

LeafView view_leaves(const HierarchicalSolution& s, const Roots& roots, int width, int height) {
  LeafView view{.camera = *roots.scene.camera, .width = width, .height = height, .leaf = {}};
  const PinholeCamera camera(view.camera.eye, view.camera.target, view.camera.up,
                             view.camera.vertical_fov_degrees, width, height);
  view.leaf.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), -1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = camera.pixel_ray(x, y);
      double nearest = std::numeric_limits<double>::infinity();
      int root = -1;
      for (std::size_t r = 0; r < s.hierarchy.roots; ++r)
        if (const double t = hit_patch(ray, s.hierarchy.elements[r].patch); t < nearest)
          nearest = t, root = static_cast<int>(r);
      if (root >= 0)
        view.leaf[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)] = leaf_at(s.hierarchy, root, ray.at(nearest));
    }
  return view;
}

double exposure_for(const HierarchicalSolution& s) {
  std::vector<double> levels;
  for (int e : leaves(s.hierarchy))
    if (is_black(s.hierarchy[e].patch.emission)) levels.push_back(max_channel(s.hierarchy[e].radiosity));
  if (levels.empty()) return 1.0;
  const std::size_t k = levels.size() * 95 / 100;
  std::nth_element(levels.begin(), levels.begin() + static_cast<std::ptrdiff_t>(k), levels.end());
  return levels[k] > 0 ? 0.85 / levels[k] : 1.0;
}

Image leaf_image(const LeafView& view, const HierarchicalSolution& s, double exposure, bool edges) {
  Image image(view.width, view.height);
  const auto at = [&](int x, int y) {
    return view.leaf[static_cast<std::size_t>(y) * static_cast<std::size_t>(view.width) +
                     static_cast<std::size_t>(x)];
  };
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const int leaf = at(x, y);
      if (leaf < 0) continue;
      image.at(x, y) = exposure * s.hierarchy[leaf].radiosity;
      if (edges &&
          ((x + 1 < view.width && at(x + 1, y) != leaf) || (y + 1 < view.height && at(x, y + 1) != leaf)))
        image.at(x, y) = Color(0.15);
    }
  return image;
}

int draw_links(Image& image, const LeafView& view, const HierarchicalSolution& s, int element) {
  const Projector p = projector(view);
  const ElementHierarchy& h = s.hierarchy;
  int drawn = 0;
  for (const Link& l : h.links)
    for (int e = element; e >= 0; e = h[e].parent) {
      if (l.receiver != e) continue;
      const Color colour = e == element ? Color(1.0, 0.85, 0.1) : Color(0.2, 0.55, 1.0);
      draw_segment(image, p, h[e].patch.centroid, h[l.source].patch.centroid, colour);
      const std::vector<Point3>& v = h[l.source].patch.vertices;
      for (std::size_t k = 0; k < v.size(); ++k) draw_segment(image, p, v[k], v[(k + 1) % v.size()], colour);
      ++drawn;
    }
  return drawn;
}

int brightest_leaf(const HierarchicalSolution& s) {
  int best = -1;
  double brightest = -1;
  for (int e : leaves(s.hierarchy))
    if (is_black(s.hierarchy[e].patch.emission) && max_channel(s.hierarchy[e].radiosity) > brightest)
      best = e, brightest = max_channel(s.hierarchy[e].radiosity);
  return best;
}

}  // namespace illum::lesson14
