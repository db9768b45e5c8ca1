// §8 Export: PLY and OBJ with per-vertex colours.
//
// The figure's solution with extrapolated vertex radiosity, T-vertices
// resolved (no cracks), exposed to sRGB bytes, written as binary and ASCII
// PLY and as OBJ with vertex colours (io/mesh_export.hpp); --ply writes the
// binary PLY elsewhere too.
#include <iostream>
#include <string>
#include <vector>

#include "element_render.hpp"
#include "illum/io/mesh_export.hpp"
#include "studies.hpp"

namespace illum::lesson12 {

void s08_export(OutputFolder& out, const Settings& settings, const Solved& s) {
  std::vector<Color> value = extrapolated_vertex_radiosity(s.shared, s.solution.element_radiosity);
  resolve_t_vertices(s.shared, value);
  const double exposure = exposure_for(s.mesh, s.solution.element_radiosity);
  ColouredMesh mesh{.positions = s.shared.positions, .colours = {}, .faces = display_polygons(s.shared)};
  for (const Color& v : value)
    mesh.colours.push_back({to_srgb8(exposure * v.r), to_srgb8(exposure * v.g), to_srgb8(exposure * v.b)});
  const std::string comment = "illum lesson 12: " + s.scene.name + ", extrapolated vertex radiosity";
  write_ply_file(out.path("cornell_box.ply"), mesh, PlyEncoding::binary_little_endian, comment);
  out.add_file("mesh", "cornell_box.ply",
               "The solved box, binary PLY with per-vertex colours (MeshLab, Blender)");
  write_ply_file(out.path("cornell_box_ascii.ply"), mesh, PlyEncoding::ascii, comment);
  out.add_file("mesh", "cornell_box_ascii.ply", "The same mesh as ASCII PLY");
  write_obj_file(out.path("cornell_box.obj"), mesh, comment);
  out.add_file("mesh", "cornell_box.obj", "The same mesh as OBJ with vertex colours (v x y z r g b)");
  if (!settings.ply.empty()) write_ply_file(settings.ply, mesh, PlyEncoding::binary_little_endian, comment);
  std::cout << "Export: " << mesh.positions.size() << " vertices, " << mesh.faces.size() << " faces\n";
}

}  // namespace illum::lesson12
