#pragma once
// Lesson 12: a mesh with one colour per vertex written for other programs
// (MeshLab, Blender): PLY, ASCII or binary (Stanford's polygon format,
// with the red, green, blue vertex properties both programs read), and
// Wavefront OBJ with the common "v x y z r g b" vertex-colour extension.
#include <array>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "illum/core/vec.hpp"

namespace illum {

// Invariants: colours.size() == positions.size(); every face lists 3 to 255
// vertex indices in range, counter-clockwise seen from its front.
struct ColouredMesh {
  std::vector<Point3> positions;
  std::vector<std::array<std::uint8_t, 3>> colours;  // 8-bit sRGB per vertex
  std::vector<std::vector<int>> faces;
};

enum class PlyEncoding { ascii, binary_little_endian };

// Throws std::invalid_argument when the mesh breaks an invariant.
void check_coloured_mesh(const ColouredMesh& mesh);

// PLY: positions as float x, y, z, colours as uchar red, green, blue, faces as
// "property list uchar int vertex_indices". `comment` goes in the header.
void write_ply(std::ostream& out, const ColouredMesh& mesh, PlyEncoding encoding,
               const std::string& comment = "");
// OBJ: "v x y z r g b" (colours in [0, 1]) and "f i j k …" (1-based).
void write_obj(std::ostream& out, const ColouredMesh& mesh, const std::string& comment = "");

// The same, written atomically to a file (system/atomic_file.hpp).
void write_ply_file(const std::filesystem::path& path, const ColouredMesh& mesh, PlyEncoding encoding,
                    const std::string& comment = "");
void write_obj_file(const std::filesystem::path& path, const ColouredMesh& mesh,
                    const std::string& comment = "");

}  // namespace illum
