#include "illum/accel/item_buffer.hpp"

#include "illum/core/error.hpp"
#include "illum/geometry/hemicube_raster.hpp"

namespace illum {

ItemBuffer ItemBuffer::render(const PinholeCamera& camera, const TriangleSet& set, double near) {
  require(near > 0, "ItemBuffer::render: near must be positive");
  const int width = camera.width(), height = camera.height();
  // The face's window spans |b'/w| ≤ 1 in units of width/2: an image taller than wide would not fit.
  require(width >= height, "ItemBuffer::render: the image must be at least as wide as it is tall");
  // The camera's image plane, recovered from its own rays: the unit forward f,
  // the top-left corner c and the steps per pixel (right, down), all at w = 1.
  const Vec3 f = camera.ray_through(0.5 * width, 0.5 * height).direction;
  const auto on_plane = [&](double x, double y) {
    const Vec3 d = camera.ray_through(x, y).direction;
    return d / dot(d, f);
  };
  const Vec3 corner = on_plane(0, 0);
  const Vec3 right = on_plane(1, 0) - corner, down = on_plane(0, 1) - corner;
  const Vec3 rx = right / dot(right, right), ry = down / dot(down, down);
  const double cx = dot(corner, rx), cy = dot(corner, ry);
  const Point3 eye = camera.eye();
  // Face coordinates (a', b', w) of a point, see the header.
  const auto to_face = [&](const Point3& p) {
    const Vec3 q = p - eye;
    const double w = dot(q, f), xw = dot(q, rx) - cx * w, yw = dot(q, ry) - cy * w;
    return Vec3(2 * xw / width - w, 2 * (height * w - yw) / width - w, w);
  };

  ItemBuffer buffer;
  buffer.width = width, buffer.height = height;
  std::vector<std::int32_t> items(static_cast<std::size_t>(width) * height, -1);
  std::vector<double> depth(items.size(), 0.0);
  const FaceTarget target{.items = items.data(),
                          .inv_depth = depth.data(),
                          .width = width,
                          .height = height,
                          .side = false,
                          .near = near};
  RasterScratch scratch;
  for (std::size_t t = 0; t < set.size(); ++t) {
    const Triangle& tri = set.triangles[t];
    const Vec3 v[3] = {to_face(tri.a), to_face(tri.b), to_face(tri.c)};
    const Vec3 n = cross(v[1] - v[0], v[2] - v[0]);
    const double d = dot(n, v[0]);
    if (d == 0) continue;  // the plane passes through the eye: seen edge-on, covers no area
    rasterize_polygon(v, 3, n, d, static_cast<std::int32_t>(t), target, scratch);
  }
  // The face's rows run upwards; the image's run downwards.
  buffer.items.resize(items.size());
  buffer.inverse_depth.resize(items.size());
  for (int r = 0; r < height; ++r)
    for (int i = 0; i < width; ++i) {
      const std::size_t from = static_cast<std::size_t>(r) * width + i;
      const std::size_t to = static_cast<std::size_t>(height - 1 - r) * width + i;
      buffer.items[to] = items[from];
      buffer.inverse_depth[to] = depth[from];
    }
  return buffer;
}

}  // namespace illum
