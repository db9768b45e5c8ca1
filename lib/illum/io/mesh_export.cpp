#include "illum/io/mesh_export.hpp"

#include <bit>
#include <cstring>
#include <iomanip>

#include "illum/core/error.hpp"
#include "illum/system/atomic_file.hpp"

namespace illum {
namespace {

// Little-endian bytes of a 4-byte value, whatever the machine's order.
template <class T>
void put_little_endian(std::ostream& out, T value) {
  static_assert(sizeof(T) == 4);
  unsigned char bytes[4];
  std::memcpy(bytes, &value, 4);
  if constexpr (std::endian::native == std::endian::big) {
    std::swap(bytes[0], bytes[3]);
    std::swap(bytes[1], bytes[2]);
  }
  out.write(reinterpret_cast<const char*>(bytes), 4);
}

}  // namespace

void check_coloured_mesh(const ColouredMesh& mesh) {
  require(mesh.colours.size() == mesh.positions.size(), "coloured mesh: one colour per vertex is needed");
  const auto n = static_cast<long long>(mesh.positions.size());
  for (const std::vector<int>& face : mesh.faces) {
    require(face.size() >= 3 && face.size() <= 255, "coloured mesh: a face has 3 to 255 vertices");
    for (int v : face) require(v >= 0 && v < n, "coloured mesh: a face names a vertex out of range");
  }
}

void write_ply(std::ostream& out, const ColouredMesh& mesh, PlyEncoding encoding,
               const std::string& comment) {
  check_coloured_mesh(mesh);
  const bool binary = encoding == PlyEncoding::binary_little_endian;
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n";
  if (!comment.empty()) out << "comment " << comment << '\n';
  out << "element vertex " << mesh.positions.size()
      << "\nproperty float x\nproperty float y\nproperty float z\n"
         "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "element face " << mesh.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  if (binary) {
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      for (int axis = 0; axis < 3; ++axis)
        put_little_endian(out, static_cast<float>(mesh.positions[v][axis]));
      out.write(reinterpret_cast<const char*>(mesh.colours[v].data()), 3);
    }
    for (const std::vector<int>& face : mesh.faces) {
      out.put(static_cast<char>(face.size()));
      for (int v : face) put_little_endian(out, static_cast<std::int32_t>(v));
    }
    return;
  }
  out << std::setprecision(9);  // a float's 24 bits round-trip in 9 digits
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    out << static_cast<float>(mesh.positions[v].x) << ' ' << static_cast<float>(mesh.positions[v].y) << ' '
        << static_cast<float>(mesh.positions[v].z) << ' ' << int(mesh.colours[v][0]) << ' '
        << int(mesh.colours[v][1]) << ' ' << int(mesh.colours[v][2]) << '\n';
  for (const std::vector<int>& face : mesh.faces) {
    out << face.size();
    for (int v : face) out << ' ' << v;
    out << '\n';
  }
}

void write_obj(std::ostream& out, const ColouredMesh& mesh, const std::string& comment) {
  check_coloured_mesh(mesh);
  if (!comment.empty()) out << "# " << comment << '\n';
  out << std::setprecision(9);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    out << "v " << mesh.positions[v].x << ' ' << mesh.positions[v].y << ' ' << mesh.positions[v].z << ' '
        << mesh.colours[v][0] / 255.0 << ' ' << mesh.colours[v][1] / 255.0 << ' '
        << mesh.colours[v][2] / 255.0 << '\n';
  for (const std::vector<int>& face : mesh.faces) {
    out << 'f';
    for (int v : face) out << ' ' << v + 1;
    out << '\n';
  }
}

void write_ply_file(const std::filesystem::path& path, const ColouredMesh& mesh, PlyEncoding encoding,
                    const std::string& comment) {
  check_coloured_mesh(mesh);
  write_file_atomically(path, [&](std::ostream& out) { write_ply(out, mesh, encoding, comment); });
}

void write_obj_file(const std::filesystem::path& path, const ColouredMesh& mesh, const std::string& comment) {
  check_coloured_mesh(mesh);
  write_file_atomically(path, [&](std::ostream& out) { write_obj(out, mesh, comment); });
}

}  // namespace illum
