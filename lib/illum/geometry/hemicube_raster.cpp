#include "illum/geometry/hemicube_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace illum {

namespace {

// Signed distance-like value of p to frustum plane k: ≥ 0 inside.
inline double plane_value(int k, const Vec3& p, const FaceTarget& t) {
  switch (k) {
    case 0:
      return p.z - t.near;  // near plane
    case 1:
      return p.z + p.x;  // a ≥ −w
    case 2:
      return p.z - p.x;  // a ≤ w
    case 3:
      return p.z - p.y;  // b ≤ w
    default:
      return t.side ? p.y : p.z + p.y;  // b ≥ 0 (the patch's plane) or b ≥ −w
  }
}

// Sutherland–Hodgman against one plane. The crossing point is always
// interpolated from the inside endpoint towards the outside one, so that
// two polygons sharing the edge compute the same point.
int clip_against(int k, const std::vector<Vec3>& in, int count, std::vector<Vec3>& out, const FaceTarget& t) {
  int n = 0;
  Vec3 prev = in[count - 1];
  double dp = plane_value(k, prev, t);
  for (int v = 0; v < count; ++v) {
    const Vec3 cur = in[v];
    const double dc = plane_value(k, cur, t);
    if (dc >= 0) {
      if (dp < 0) out[n++] = cur + (dc / (dc - dp)) * (prev - cur);
      out[n++] = cur;
    } else if (dp >= 0) {
      out[n++] = prev + (dp / (dp - dc)) * (cur - prev);
    }
    prev = cur;
    dp = dc;
  }
  return n;
}

// ⌈y⌉ for |y| < 2³¹ (every pixel coordinate here): the same integer as
// static_cast<int>(std::ceil(y)), without the library's general rounding, which
// the release build (plain x86-64, no SSE4.1 round instruction) spells out in
// about ten instructions; the rasteriser takes four to six per polygon and two
// per row. Truncation rounds towards zero, so only a positive non-integer y
// needs the step up.
inline int ceil_to_int(double y) {
  const int t = static_cast<int>(y);
  return t + (static_cast<double>(t) < y ? 1 : 0);
}

}  // namespace

unsigned frustum_outcode(const Vec3& p, const FaceTarget& target) {
  unsigned code = 0;
  for (int k = 0; k < 5; ++k)
    if (plane_value(k, p, target) < 0) code |= 1u << k;
  return code;
}

int rasterize_polygon(const Vec3* vertices, int count, const Vec3& plane_normal, double plane_d,
                      std::int32_t item, const FaceTarget& t, RasterScratch& s) {
  if (count < 3) return 0;
  unsigned all = ~0u, any = 0;
  for (int v = 0; v < count; ++v) {
    const unsigned c = frustum_outcode(vertices[v], t);
    all &= c;
    any |= c;
  }
  if (all != 0) return 0;  // every vertex outside one plane: nothing to draw

  // 1. Clip (only against the planes some vertex is outside of). Each plane
  // adds at most one vertex to a convex polygon.
  const std::size_t capacity = static_cast<std::size_t>(count) + 6;
  if (s.clip_a.size() < capacity) s.clip_a.resize(capacity), s.clip_b.resize(capacity);
  int n = count;
  const Vec3* polygon = vertices;  // wholly inside (the usual case at fine meshes): no copy, no clipping
  if (any != 0) {
    std::copy(vertices, vertices + count, s.clip_a.begin());
    for (int k = 0; k < 5 && n >= 3; ++k)
      if (any & (1u << k)) {
        n = clip_against(k, s.clip_a, n, s.clip_b, t);
        std::swap(s.clip_a, s.clip_b);
      }
    if (n < 3) return 0;
    polygon = s.clip_a.data();
  }

  // 2. Project to pixel coordinates (into clip_a, which `polygon` may alias:
  // each vertex is read before it is written).
  if (s.vertex_row.size() < s.clip_a.size()) s.vertex_row.resize(s.clip_a.size());
  for (int v = 0; v < n; ++v) {
    const Vec3 p = polygon[v];
    s.vertex_row[v] = project_to_pixel(p, t, s.clip_a[v]);
  }
  return scan_projected(n, plane_normal, plane_d, item, t, s);
}

// A vertex's first row at or above it, ⌈Y − ½⌉, is rounded once here and shared by its two edges
// and the polygon's row range (rounding is monotone, so the lowest is the row range's start).
int project_to_pixel(const Vec3& p, const FaceTarget& t, Vec3& pixel) {
  const double half_w = 0.5 * t.width;
  pixel = Vec3((p.x / p.z + 1.0) * half_w, (p.y / p.z + (t.side ? 0.0 : 1.0)) * half_w, 0.0);
  return ceil_to_int(pixel.y - 0.5);
}

int scan_projected(int n, const Vec3& plane_normal, double plane_d, std::int32_t item, const FaceTarget& t,
                   RasterScratch& s) {
  // 3. Spans: for each row whose centre Y = r + ½ lies in [Y_low, Y_high) of
  // an edge, the edge's X there. A convex polygon has a left and a right edge.
  if (static_cast<int>(s.span_left.size()) < t.height) {
    s.span_left.resize(t.height);
    s.span_right.resize(t.height);
  }
  int row_low = s.vertex_row[0], row_high = row_low;
  double x_low = s.clip_a[0].x, x_high = x_low;
  for (int v = 1; v < n; ++v) {
    row_low = std::min(row_low, s.vertex_row[v]), row_high = std::max(row_high, s.vertex_row[v]);
    x_low = std::min(x_low, s.clip_a[v].x), x_high = std::max(x_high, s.clip_a[v].x);
  }
  const int row_begin = std::max(0, row_low);
  const int row_end = std::min(t.height, row_high);
  if (row_begin >= row_end) return 0;
  // No column centre between the lowest and the highest X: no span can hold one either (a span's
  // ends are points of edges, between their vertices' X). Most polygons of a fine mesh stop here
  // or above, smaller than a pixel.
  if (std::max(0, ceil_to_int(x_low - 0.5)) >= std::min(t.width, ceil_to_int(x_high - 0.5))) return 0;
  std::fill(s.span_left.begin() + row_begin, s.span_left.begin() + row_end,
            std::numeric_limits<double>::infinity());
  std::fill(s.span_right.begin() + row_begin, s.span_right.begin() + row_end,
            -std::numeric_limits<double>::infinity());
  // Edge (prev, v) for each v: no modulo (an integer division) per edge.
  for (int v = 0, prev = n - 1; v < n; prev = v++) {
    Vec3 p0 = s.clip_a[prev], p1 = s.clip_a[v];
    int q0 = s.vertex_row[prev], q1 = s.vertex_row[v];
    if (p0.y == p1.y) continue;  // horizontal edges cover no row centre on their own
    if (p0.y > p1.y)
      std::swap(p0, p1), std::swap(q0, q1);  // walk every edge upwards, whichever polygon it belongs to
    const int r0 = std::max(row_begin, q0);
    const int r1 = std::min(row_end, q1);
    if (r0 >= r1) continue;  // no row centre on this edge: no slope to divide for
    const double slope = (p1.x - p0.x) / (p1.y - p0.y);
    for (int r = r0; r < r1; ++r) {
      const double x = p0.x + (r + 0.5 - p0.y) * slope;
      s.span_left[r] = std::min(s.span_left[r], x);
      s.span_right[r] = std::max(s.span_right[r], x);
    }
  }

  // 4. 1/w on the plane n·p = d along the direction (a', b', 1) is (n·(a', b', 1))/d,
  // with a' = 2X/res − 1 and b' = 2Y/res − 1 (top) or 2Y/res (sides): affine in (X, Y).
  const double scale = 2.0 / t.width;
  const double ka = plane_normal.x / plane_d * scale, kb = plane_normal.y / plane_d * scale;
  const double k0 = (plane_normal.z - plane_normal.x - (t.side ? 0.0 : plane_normal.y)) / plane_d;
  int written = 0;
  for (int r = row_begin; r < row_end; ++r) {
    if (!(s.span_left[r] < s.span_right[r])) continue;  // an empty or degenerate span
    const int c0 = std::max(0, ceil_to_int(s.span_left[r] - 0.5));
    const int c1 = std::min(t.width, ceil_to_int(s.span_right[r] - 0.5));
    if (c0 >= c1) continue;
    std::int32_t* items = t.items + static_cast<std::ptrdiff_t>(r) * t.width;
    double* depth = t.inv_depth + static_cast<std::ptrdiff_t>(r) * t.width;
    const double row_term = kb * (r + 0.5) + k0;
    // Branch-free: whether a pixel is nearer changes from pixel to pixel in
    // the scattered small polygons of a fine mesh, so a branch mispredicts.
    for (int c = c0; c < c1; ++c) {
      const double inv_w = ka * (c + 0.5) + row_term;
      const bool nearer = inv_w > depth[c];
      depth[c] = nearer ? inv_w : depth[c];
      items[c] = nearer ? item : items[c];
      written += nearer ? 1 : 0;
    }
  }
  return written;
}

}  // namespace illum
