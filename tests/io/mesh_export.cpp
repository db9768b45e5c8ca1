// PLY and OBJ export (lesson 12), read back by a reader written here from
// the PLY specification, independently of the writer: it parses the header
// line by line, then the body as ASCII or as little-endian binary, by the
// properties the header declares (not by the layout the writer happens to use).
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "illum/io/mesh_export.hpp"

using namespace illum;

namespace {

struct ReadPly {
  std::string format;
  std::vector<std::vector<double>> vertices;  // one value per declared vertex property, in order
  std::vector<std::string> vertex_properties;
  std::vector<std::vector<long long>> faces;
};

std::size_t type_size(const std::string& type) {
  static const std::map<std::string, std::size_t> sizes = {
      {"char", 1},  {"uchar", 1},  {"short", 2},   {"ushort", 2}, {"int", 4},
      {"uint", 4},  {"float", 4},  {"double", 8},  {"int8", 1},   {"uint8", 1},
      {"int32", 4}, {"uint32", 4}, {"float32", 4}, {"float64", 8}};
  return sizes.at(type);
}

// One little-endian binary value of a PLY scalar type, as a double.
double read_binary(std::istream& in, const std::string& type) {
  unsigned char b[8] = {};
  in.read(reinterpret_cast<char*>(b), static_cast<std::streamsize>(type_size(type)));
  std::uint64_t bits = 0;
  for (std::size_t i = type_size(type); i-- > 0;) bits = (bits << 8) | b[i];
  if (type == "float" || type == "float32") {
    const auto u = static_cast<std::uint32_t>(bits);
    float f;
    std::memcpy(&f, &u, 4);
    return f;
  }
  if (type == "uchar" || type == "uint8") return static_cast<double>(bits);
  if (type == "int" || type == "int32") return static_cast<double>(static_cast<std::int32_t>(bits));
  throw std::runtime_error("test reader: unexpected type " + type);
}

ReadPly read_ply(std::istream& in) {
  ReadPly ply;
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "ply");
  std::size_t vertex_count = 0, face_count = 0;
  std::vector<std::string> vertex_types;
  std::string element, count_type, index_type;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") words >> ply.format;
    if (word == "element") {
      std::size_t count;
      words >> element >> count;
      (element == "vertex" ? vertex_count : face_count) = count;
    }
    if (word == "property" && element == "vertex") {
      std::string type, name;
      words >> type >> name;
      vertex_types.push_back(type);
      ply.vertex_properties.push_back(name);
    }
    if (word == "property" && element == "face") words >> word >> count_type >> index_type;
  }
  REQUIRE(line == "end_header");
  const bool binary = ply.format == "binary_little_endian";
  for (std::size_t v = 0; v < vertex_count; ++v) {
    std::vector<double> values;
    for (const std::string& type : vertex_types) {
      double x = 0;
      if (binary)
        x = read_binary(in, type);
      else
        in >> x;
      values.push_back(x);
    }
    ply.vertices.push_back(values);
  }
  for (std::size_t f = 0; f < face_count; ++f) {
    double n = 0;
    if (binary)
      n = read_binary(in, count_type);
    else
      in >> n;
    std::vector<long long> face;
    for (int k = 0; k < static_cast<int>(n); ++k) {
      double index = 0;
      if (binary)
        index = read_binary(in, index_type);
      else
        in >> index;
      face.push_back(static_cast<long long>(index));
    }
    ply.faces.push_back(face);
  }
  REQUIRE_MESSAGE(in.good(), "the body ended before the header's counts were read");
  return ply;
}

// Two unit squares sharing an edge, and a triangle: 7 vertices, colours chosen per vertex.
ColouredMesh sample_mesh() {
  ColouredMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {0.5, 2.25, -1.5}};
  for (int v = 0; v < 7; ++v)
    m.colours.push_back({static_cast<std::uint8_t>(10 * v), static_cast<std::uint8_t>(255 - v),
                         static_cast<std::uint8_t>(v == 6 ? 0 : 128)});
  m.faces = {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 6}};
  return m;
}

void check_read_back(const ReadPly& ply, const ColouredMesh& m) {
  REQUIRE(ply.vertices.size() == m.positions.size());
  REQUIRE(ply.vertex_properties == std::vector<std::string>{"x", "y", "z", "red", "green", "blue"});
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    INFO("vertex " << v);
    for (int axis = 0; axis < 3; ++axis)
      CHECK(ply.vertices[v][axis] == doctest::Approx(m.positions[v][axis]));
    for (int c = 0; c < 3; ++c) CHECK(ply.vertices[v][3 + c] == m.colours[v][c]);
  }
  REQUIRE(ply.faces.size() == 3);
  CHECK(ply.faces[0] == std::vector<long long>{0, 1, 4, 3});
  CHECK(ply.faces[1] == std::vector<long long>{1, 2, 5, 4});
  CHECK(ply.faces[2] == std::vector<long long>{3, 4, 6});
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("PLY, ASCII and binary, reads back with the same vertices, colours and faces") {
    const ColouredMesh m = sample_mesh();
    for (PlyEncoding encoding : {PlyEncoding::ascii, PlyEncoding::binary_little_endian}) {
      std::stringstream text(std::ios::in | std::ios::out | std::ios::binary);
      write_ply(text, m, encoding, "a test");
      const ReadPly ply = read_ply(text);
      CHECK(ply.format == (encoding == PlyEncoding::ascii ? "ascii" : "binary_little_endian"));
      check_read_back(ply, m);
      if (encoding == PlyEncoding::ascii) text >> std::ws;  // the last line's newline
      char extra;
      CHECK_MESSAGE(!text.get(extra), "nothing follows the last face");
    }
  }

  TEST_CASE("a PLY file written to disk reads back, and its binary body has the size the header implies") {
    const ColouredMesh m = sample_mesh();
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "illum_test_mesh_export.ply";
    write_ply_file(path, m, PlyEncoding::binary_little_endian);
    std::ifstream in(path, std::ios::binary);
    check_read_back(read_ply(in), m);
    // 7 vertices × (3 floats + 3 bytes) + faces (1 + 4·4) + (1 + 4·4) + (1 + 3·4) = 105 + 47 bytes.
    std::ifstream whole(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
    CHECK(bytes.size() - (bytes.find("end_header\n") + 11) == 7 * 15 + 17 + 17 + 13);
    std::filesystem::remove(path);
  }

  TEST_CASE("OBJ lists v x y z r g b with colours in [0, 1] and 1-based faces") {
    std::stringstream text;
    write_obj(text, sample_mesh());
    std::vector<std::vector<double>> v;
    std::vector<std::vector<int>> f;
    std::string line;
    while (std::getline(text, line)) {
      std::istringstream words(line);
      std::string tag;
      words >> tag;
      std::vector<double> numbers;
      for (double x; words >> x;) numbers.push_back(x);
      if (tag == "v") v.push_back(numbers);
      if (tag == "f") f.push_back(std::vector<int>(numbers.begin(), numbers.end()));
    }
    REQUIRE(v.size() == 7);
    CHECK(v[6][1] == doctest::Approx(2.25));
    CHECK(v[2][3] == doctest::Approx(20 / 255.0));  // red of vertex 2 is 20
    CHECK(v[6][5] == doctest::Approx(0.0));
    REQUIRE(f.size() == 3);
    CHECK(f[2] == std::vector<int>{4, 5, 7});
  }

  TEST_CASE("a coloured mesh with a face out of range or a missing colour is refused") {
    ColouredMesh m = sample_mesh();
    m.faces.push_back({0, 1, 7});
    std::ostringstream sink;
    CHECK_THROWS_AS(write_ply(sink, m, PlyEncoding::ascii), std::invalid_argument);
    m = sample_mesh();
    m.colours.pop_back();
    CHECK_THROWS_AS(write_obj(sink, m), std::invalid_argument);
    m = sample_mesh();
    m.faces.push_back({0, 1});
    CHECK_THROWS_AS(write_ply(sink, m, PlyEncoding::binary_little_endian), std::invalid_argument);
  }
}
