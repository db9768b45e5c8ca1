// Fuzz target: the OBJ reader of scene meshes (io/obj_reader). Any bytes give
// either a TriangleMesh that keeps the reader's promises or an
// illum::InputFileError; never a crash, a hang, another exception, undefined
// behaviour (the build adds ASan, UBSan and float-cast-overflow) or a mesh
// that breaks them: every index within the positions, every position finite,
// every shading normal of unit length, every triangle of non-zero area.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "illum/io/obj_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  illum::TriangleMesh mesh;
  try {
    mesh = illum::read_obj(text);
  } catch (const illum::InputFileError&) {
    return 0;  // the expected refusal
  }
  if (mesh.triangles.empty()) std::abort();
  for (const illum::Point3& p : mesh.positions)
    if (!illum::is_finite(p)) std::abort();
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t i : t)
      if (i >= mesh.positions.size()) std::abort();
    const illum::Vec3 area = illum::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                          mesh.positions[t[2]] - mesh.positions[t[0]]);
    if (area == illum::Vec3(0.0) || !illum::is_finite(area)) std::abort();
  }
  if (!mesh.corner_normals.empty()) {
    if (mesh.corner_normals.size() != 3 * mesh.triangles.size()) std::abort();
    for (const illum::Vec3& n : mesh.corner_normals)
      if (!(std::abs(illum::length(n) - 1.0) < 1e-9)) std::abort();
  }
  return 0;
}
