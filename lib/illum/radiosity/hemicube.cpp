#include "illum/radiosity/hemicube.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illum/core/error.hpp"
#include "illum/core/frame.hpp"
#include "illum/core/random.hpp"

namespace illum {

using std::numbers::pi;  // π is the standard's: no file defines its own

namespace {

std::size_t face_offset(int res, HemicubeFace f) {
  const std::size_t top = static_cast<std::size_t>(res) * res,
                    side = static_cast<std::size_t>(res) * (res / 2);
  const int k = static_cast<int>(f);
  return k == 0 ? 0 : top + static_cast<std::size_t>(k - 1) * side;
}

// A face's view frame (a, b, w) from the hemicube's frame (x, y, z): w is
// the face's axis; for the sides b = z, the height above the patch.
inline Vec3 to_face(HemicubeFace f, const Vec3& p) {
  switch (f) {
    case HemicubeFace::top:
      return p;
    case HemicubeFace::pos_x:
      return Vec3(p.y, p.z, p.x);
    case HemicubeFace::neg_x:
      return Vec3(-p.y, p.z, -p.x);
    case HemicubeFace::pos_y:
      return Vec3(-p.x, p.z, p.y);
    default:
      return Vec3(p.x, p.z, -p.y);
  }
}

}  // namespace

const std::int32_t* HemicubeBuffers::face_items(HemicubeFace f) const {
  require(resolution > 0, "HemicubeBuffers::face_items: the buffers hold no hemicube yet");
  return items.data() + face_offset(resolution, f);
}

bool hemicube_pixel(const Vec3& d, int resolution, HemicubeFace& face, int& col, int& row) {
  if (!(d.z >= 0) || (d.x == 0 && d.y == 0 && d.z == 0)) return false;
  // The face whose axis has the largest component (the top face wins ties with d.z).
  const double ax = std::abs(d.x), ay = std::abs(d.y);
  if (d.z >= ax && d.z >= ay)
    face = HemicubeFace::top;
  else if (ax >= ay)
    face = d.x > 0 ? HemicubeFace::pos_x : HemicubeFace::neg_x;
  else
    face = d.y > 0 ? HemicubeFace::pos_y : HemicubeFace::neg_y;
  const Vec3 f = to_face(face, d);
  const int height = HemicubeBuffers::face_height(resolution, face);
  col = std::clamp(static_cast<int>((f.x / f.z + 1.0) * 0.5 * resolution), 0, resolution - 1);
  row = std::clamp(static_cast<int>((f.y / f.z + (face == HemicubeFace::top ? 1.0 : 0.0)) * 0.5 * resolution),
                   0, height - 1);
  return true;
}

Hemicube::Hemicube(int resolution, DeltaRule rule) : deltas_(make_hemicube_deltas(resolution, rule)) {}

void Hemicube::form_factor_row(const std::vector<Patch>& patches, std::size_t i, double* row,
                               HemicubeBuffers& buffers, double rotation_angle) const {
  require(i < patches.size(), "Hemicube::form_factor_row: patch index i is out of range");
  require(row != nullptr, "Hemicube::form_factor_row: row is null");
  require(std::isfinite(rotation_angle), "Hemicube::form_factor_row: rotation_angle must be finite");
  const int res = resolution();
  const std::size_t pixels =
      face_offset(res, HemicubeFace::neg_y) + static_cast<std::size_t>(res) * (res / 2);
  if (buffers.resolution != res) {
    buffers.resolution = res;
    buffers.items.assign(pixels, kEmptyPixel);
    buffers.inv_depth.assign(pixels, 0.0);
  } else {
    std::fill(buffers.items.begin(), buffers.items.end(), kEmptyPixel);
    std::fill(buffers.inv_depth.begin(), buffers.inv_depth.end(), 0.0);
  }

  // The hemicube's frame: z along the receiver's normal, x and y turned by
  // rotation_angle about it.
  const Patch& receiver = patches[i];
  const Vec3 z = receiver.normal;
  const Frame frame = Frame::around(z);
  const Vec3 &t = frame.t1, &b = frame.t2;
  const double cs = std::cos(rotation_angle), sn = std::sin(rotation_angle);
  const Vec3 x = cs * t + sn * b, y = -sn * t + cs * b;
  const Point3 eye = receiver.centroid;

  FaceTarget targets[5];
  for (int k = 0; k < 5; ++k) {
    const auto f = static_cast<HemicubeFace>(k);
    const std::size_t off = face_offset(res, f);
    targets[k] = FaceTarget{
        buffers.items.data() + off, buffers.inv_depth.data() + off, res, HemicubeBuffers::face_height(res, f),
        f != HemicubeFace::top,     1e-9 * std::sqrt(receiver.area)};
  }

  for (std::size_t j = 0; j < patches.size(); ++j) {
    if (j == i) continue;
    const Patch& p = patches[j];
    const std::size_t nv = p.vertices.size();
    if (buffers.local.size() < nv) buffers.local.resize(nv), buffers.face.resize(nv);
    bool above = false;
    double reach = 0;
    for (std::size_t k = 0; k < nv; ++k) {
      const Vec3 d = p.vertices[k] - eye;
      buffers.local[k] = Vec3(dot(d, x), dot(d, y), dot(d, z));
      above |= buffers.local[k].z > 0;
      reach = std::max(
          reach, std::abs(buffers.local[k].z) + std::abs(buffers.local[k].x) + std::abs(buffers.local[k].y));
    }
    if (!above) continue;  // wholly behind or on the base plane: invisible from the hemicube
    // The patch's plane n·q = d in the hemicube's frame (eye at the origin).
    const Vec3 n_local(dot(p.normal, x), dot(p.normal, y), dot(p.normal, z));
    const double d = dot(p.normal, p.vertices[0] - eye);
    if (std::abs(d) <= 1e-12 * reach) continue;  // seen exactly edge-on: projects to a line
    // d < 0: the eye is in front of the patch. Otherwise we see its back,
    // which still hides what lies behind it but receives nothing.
    const std::int32_t item = d < 0 ? static_cast<std::int32_t>(j) : kBackFacePixel;
    // A back face meets a front face at a silhouette edge, where both project onto the
    // same side of the edge with the same depth: a ray exactly through the edge would
    // tie. Pushing back faces a relative 1e-9 further makes the front face win the tie.
    const double plane_d = d < 0 ? d : d * (1.0 + 1e-9);
    for (int k = 0; k < 5; ++k) {
      const auto f = static_cast<HemicubeFace>(k);
      for (std::size_t v = 0; v < nv; ++v) buffers.face[v] = to_face(f, buffers.local[v]);
      rasterize_polygon(buffers.face.data(), static_cast<int>(nv), to_face(f, n_local), plane_d, item,
                        targets[k], buffers.raster);
    }
  }

  // F_ij = Σ ΔF over the pixels showing j.
  std::fill(row, row + patches.size(), 0.0);
  accumulate_face(targets[0].items, deltas_.top.data(), deltas_.top.size(), row);
  for (int k = 1; k < 5; ++k)
    accumulate_face(targets[k].items, deltas_.side.data(), deltas_.side.size(), row);
  row[i] = 0.0;
}

FormFactorMatrix hemicube_form_factors(const std::vector<Patch>& patches, int resolution,
                                       bool random_rotation, std::uint64_t seed) {
  const Hemicube hemicube(resolution);
  FormFactorMatrix f(patches.size());
  const long n = static_cast<long>(patches.size());
#pragma omp parallel
  {
    HemicubeBuffers buffers;
#pragma omp for schedule(dynamic, 4)
    for (long i = 0; i < n; ++i) {
      // One stream per patch: the angles do not depend on the thread count.
      double angle = 0.0;
      if (random_rotation) {
        Rng rng(seed, static_cast<std::uint64_t>(i));
        angle = 2.0 * pi * rng.uniform();
      }
      hemicube.form_factor_row(patches, static_cast<std::size_t>(i), f.row(static_cast<std::size_t>(i)),
                               buffers, angle);
    }
  }
  return f;
}

}  // namespace illum
