// The strict OBJ reader (io/obj_reader) and the regular-file reader of inputs
// (system/input_file). Suite "io" (not graded). Contracts checked:
//  * v (3, 4 or 6 numbers), vn, vt and f with v, v/t, v//n, v/t/n corners are
//    read; CRLF line ends and # comments anywhere; o/g/s/usemtl/mtllib/l/p skipped;
//  * a face of n corners is the fan (1, k, k+1) of n − 2 triangles, whatever n
//    (a 300-corner face, then the next face read as written);
//  * a negative index counts back from the elements defined before its line;
//    a positive one may name an element defined later in the file;
//  * every refusal names the line, the item and the value as written: wrapped
//    and overflowing indices, index 0, counting back too far, NaN, infinity,
//    1e999 and words as numbers, faces of fewer than 3 corners (also the last,
//    cut-off line), zero normals, degenerate faces, free-form and unknown
//    statements, a file without faces;
//  * the memory a mesh will take is checked before it is filled;
//  * an input that is a FIFO, a device or a folder is refused at once, by kind.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "illum/io/obj_reader.hpp"
#include "illum/system/input_file.hpp"
#include "support/sanitized.hpp"
#include "support/throws_containing.hpp"

namespace fs = std::filesystem;
using illum::read_obj;
using illum::TriangleMesh;
using Tri = std::array<std::uint32_t, 3>;

namespace {

std::string refusal(const std::string& text) {
  try {
    (void)read_obj(text);
  } catch (const illum::InputFileError& e) {
    return e.what();
  }
  return "(accepted)";
}

using illum::test::sanitized;

// Bytes of address space this process maps now (VmSize).
double mapped_bytes() {
  std::ifstream in("/proc/self/status");
  std::string key;
  double kib = 0;
  while (in >> key)
    if (key == "VmSize:") {
      in >> kib;
      return 1024 * kib;
    }
  return 0;
}

// RLIMIT_AS set to what the process maps plus `headroom` bytes, restored on destruction.
struct AddressSpaceLimit {
  rlimit old{};
  explicit AddressSpaceLimit(double headroom) {
    getrlimit(RLIMIT_AS, &old);
    rlimit l = old;
    l.rlim_cur = static_cast<rlim_t>(mapped_bytes() + headroom);
    setrlimit(RLIMIT_AS, &l);
  }
  ~AddressSpaceLimit() { setrlimit(RLIMIT_AS, &old); }
};

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("OBJ: a quad with CRLF line ends, comments, a w and vertex colours is two fanned triangles") {
    const TriangleMesh m = read_obj(
        "# a quad\r\nv 0 0 0 1\r\nv 1 0 0 0.5 0.5 0.5\r\nv 1 1 0\r\n\r\nv 0 1 0 # corner four\r\n"
        "o quad\r\ng side\r\ns off\r\nusemtl grey\r\nf 1 2 3 4 # the face\r\nl 1 2\r\n");
    REQUIRE(m.positions.size() == 4);
    CHECK(m.positions[1] == illum::Point3(1, 0, 0));
    REQUIRE(m.triangles.size() == 2);
    CHECK(m.triangles[0] == Tri{0, 1, 2});
    CHECK(m.triangles[1] == Tri{0, 2, 3});
    CHECK(m.corner_normals.empty());  // no corner names a normal: flat shading
  }

  TEST_CASE("OBJ: a UTF-8 byte-order mark at the start is read past; anywhere else it is no statement") {
    const TriangleMesh m = read_obj("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    REQUIRE(m.positions.size() == 3);
    CHECK(m.positions[0] == illum::Point3(0, 0, 0));
    CHECK(m.triangles.size() == 1);
    CHECK(refusal("v 0 0 0\n\xEF\xBB\xBFv 1 0 0\nv 0 1 0\nf 1 2 3\n") ==
          "line 2: unknown statement '\\xef\\xbb\\xbfv' (illum reads v, vn, vt and f, and skips o, g, s, l, "
          "p, usemtl and mtllib)");
  }

  TEST_CASE("OBJ: a vertex lies within ±1e150, the bound of every coordinate of a scene") {
    // 1e150 itself is read (its square, 1e300, is a double); the next representable numbers beyond are not.
    CHECK(read_obj("v 0 0 -1e150\nv 1e150 0 0\nv 0 1 0\nf 1 2 3\n").positions[1].x == 1e150);
    const std::string x = refusal("v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK(x.find("line 2: vertex x '1e308' lies beyond ±1e150") == 0);
    CHECK(refusal("v 0 0 0\nv 0 -1.0000001e150 0\nv 0 1 0\nf 1 2 3\n").find("vertex y '-1.0000001e150'") !=
          std::string::npos);
    // A vertex's 4th to 6th numbers (w, colours) are not coordinates: not bounded.
    CHECK(read_obj("v 0 0 0 1e300\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").positions.size() == 3);
  }

  TEST_CASE("OBJ: negative indices count back from the line; positive ones may point ahead") {
    // After three vertices, -1 is the third; after a fourth, -1 is the fourth.
    const TriangleMesh m = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf -1 -2 -4\n");
    REQUIRE(m.triangles.size() == 2);
    CHECK(m.triangles[0] == Tri{0, 1, 2});
    CHECK(m.triangles[1] == Tri{3, 2, 0});
    // A face before its vertices (legal OBJ, if rare).
    const TriangleMesh ahead = read_obj("f 1 2 3\nv 0 0 0\nv 0 1 0\nv 0 0 1\n");
    REQUIRE(ahead.triangles.size() == 1);
    CHECK(ahead.triangles[0] == Tri{0, 1, 2});
  }

  TEST_CASE("OBJ: a 300-corner face is 298 triangles, and the face after it is read as written") {
    // (The loader used before counted corners in a byte: 300 wrapped to 44.)
    // ostringstream rather than string '+': GCC 12 warns falsely (-Wrestrict) on the latter.
    std::ostringstream text;
    text.precision(17);
    for (int k = 0; k < 300; ++k) {
      const double a = 2 * std::numbers::pi * k / 300;
      text << "v " << std::cos(a) << " " << std::sin(a) << " 0\n";
    }
    text << "f";
    for (int k = 1; k <= 300; ++k) text << " " << k;
    text << "\nf 10 20 30\n";
    const TriangleMesh m = read_obj(text.str());
    REQUIRE(m.triangles.size() == 298 + 1);
    CHECK(m.triangles[0] == Tri{0, 1, 2});
    CHECK(m.triangles[297] == Tri{0, 298, 299});
    CHECK(m.triangles[298] == Tri{9, 19, 29});
  }

  TEST_CASE("OBJ: normals are read for every corner, made unit, and dropped when one corner has none") {
    const TriangleMesh smooth =
        read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 3e300 4e300\nf 1//1 2//2 3//1\n");
    REQUIRE(smooth.corner_normals.size() == 3);
    CHECK(smooth.corner_normals[0] == illum::Vec3(0, 0, 1));
    // (0, 3e300, 4e300) has no length in a double, but a direction: (0, 0.6, 0.8).
    CHECK(smooth.corner_normals[1].y == doctest::Approx(0.6));
    CHECK(smooth.corner_normals[1].z == doctest::Approx(0.8));
    const TriangleMesh mixed = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1//1 2/1 3//1\n");
    CHECK(mixed.corner_normals.empty());
  }

  TEST_CASE("OBJ: each refusal names the line, the item and the value as written") {
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    struct Case {
      std::string text, words;
    };
    const Case cases[] = {
        {tri + "f 1 2 3\nf 1 2 4294967299\n",
         "line 5: vertex index '4294967299' of corner 3 is out of range"},
        {tri + "f 1 2 99999999999999999999\n", "line 4: vertex index '99999999999999999999' of corner 3"},
        {tri + "f 1 2 -18446744073709551617\n", "'-18446744073709551617' of corner 3 is out of range"},
        {tri + "f 1 2 0\n", "line 4: vertex index '0' of corner 3 is 0"},
        {tri + "f -1 -2 -5\n",
         "line 4: vertex index '-5' of corner 3 counts back 5 vertices, but 3 vertices"},
        {tri + "f 1 2 4\n",
         "line 4: vertex index '4' of corner 3 is out of range: the file defines 3 vertices"},
        {"v nan 1 0\n", "line 1: vertex x 'nan' is not a finite number"},
        {"v 0 0 0\nv 1 inf 0\n", "line 2: vertex y 'inf' is not a finite number"},
        {"v 0 0 1e999\n", "line 1: vertex z '1e999' is not a finite number"},
        {"v 0 one 1\n", "line 1: vertex y 'one' is not a number"},
        {"v 0 1.5x 1\n", "line 1: vertex y '1.5x' is not a number"},
        {"v 0 0\n", "line 1: a vertex has 3 numbers"},
        {tri + "vn 0 0\n", "line 4: a normal has 3 numbers (x y z); this one has 2"},
        {tri + "f 1 2 3\nf 1 2\n", "line 5: a face needs at least 3 corners; this one has 2"},
        {tri + "f 1 2 3\nf 1 2", "line 5: a face needs at least 3 corners"},  // the last line, cut off
        {tri + "f 1 2/ 3\n", "line 4: corner 2 '2/' ends with '/'"},
        {tri + "f 1 2/1/1/1 3\n", "corner 2 '2/1/1/1' has more than three parts"},
        {tri + "vn 0 0 0\nf 1//1 2//1 3//1\n", "line 5: normal 1 of the face is (0, 0, 0)"},
        {tri + "f 1 2 2\n", "line 4: the face is degenerate"},
        {tri + "f 1 2 3\ncurv 0 1 1 2\n", "line 5: 'curv' is free-form geometry"},
        {tri + "vx 1 2 3\n", "line 4: unknown statement 'vx'"},
        {tri, "the file has no faces (3 vertices"},
        {"", "the file has no faces"},
        {std::string("\x00\x01", 2), "line 1: unknown statement '\\x00\\x01'"},
    };
    for (const Case& c : cases) {
      CAPTURE(c.text);
      CHECK(refusal(c.text).find(c.words) != std::string::npos);
    }
    // 1e-400 underflows to zero: a number, not an error.
    CHECK(read_obj("v 1e-400 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").positions[0].x == 0.0);
  }

  TEST_CASE("OBJ: a mesh beyond the memory budget is refused before it is filled") {
    if (sanitized) return;
    // 600,000 triangles at obj_bytes_per_triangle = 512 bytes (and 3 vertices of 24): 307.2 MB,
    // against a budget of half of the 200 MB of address space left.
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < 600000; ++i) text += "f 1 2 3\n";
    const AddressSpaceLimit limit(200e6);
    const std::string e = refusal(text);
    CHECK(e.find("a mesh of 600000 triangles") != std::string::npos);
    CHECK(e.find("would need 307.2 MB") != std::string::npos);
    CHECK(e.find("ulimit -v") != std::string::npos);
  }

  TEST_CASE("input files: a FIFO, a device, a folder and a missing file are refused at once, by kind") {
    const fs::path dir = fs::temp_directory_path() / ("illum-input-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    REQUIRE(::mkfifo((dir / "pipe").c_str(), 0600) == 0);  // no writer: a blocking open would wait for ever
    ILLUM_CHECK_THROWS_CONTAINING(illum::read_input_file(dir / "pipe", "scene file", 1 << 20),
                                  "this is a named pipe (FIFO), not a regular file", illum::InputFileError);
    ILLUM_CHECK_THROWS_CONTAINING(illum::read_input_file("/dev/zero", "OBJ file", 1 << 20),
                                  "a character device, not a regular file", illum::InputFileError);
    ILLUM_CHECK_THROWS_CONTAINING(illum::read_input_file(dir, "scene file", 1 << 20), "this is a folder",
                                  illum::InputFileError);
    ILLUM_CHECK_THROWS_CONTAINING(illum::read_input_file(dir / "none", "scene file", 1 << 20),
                                  "No such file or directory", illum::InputFileError);
    fs::create_symlink(dir / "none", dir / "dangling");
    ILLUM_CHECK_THROWS_CONTAINING(illum::read_input_file(dir / "dangling", "scene file", 1 << 20),
                                  "a symbolic link to a file that does not exist", illum::InputFileError);
    std::ofstream(dir / "big") << std::string(100, 'x');
    ILLUM_CHECK_THROWS_CONTAINING(illum::read_input_file(dir / "big", "scene file", 10),
                                  "has 100 bytes; the most read is 10", illum::InputFileError);
    CHECK(illum::read_input_file(dir / "big", "scene file", 100) == std::string(100, 'x'));
    fs::remove_all(dir);
  }
}
