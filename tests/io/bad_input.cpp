// Bad input, below the programs: a failed run leaves its folder as it was,
// JSON checks that name the field without recursing, "did you mean", one
// planarity rule, patch counts refused before meshing. Suite "io" (not graded).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "illum/core/error.hpp"
#include "illum/geometry/implicit_trace.hpp"
#include "illum/io/json_text_check.hpp"
#include "illum/io/nearest_name.hpp"
#include "illum/io/program.hpp"
#include "illum/io/scene_file.hpp"
#include "illum/system/atomic_file.hpp"
#include "illum/system/memory_budget.hpp"
#include "support/throws_containing.hpp"

namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fresh folder under the build's temporary folder.
fs::path fresh_folder(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("illum-io-test-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string refusal(std::string_view text) {
  try {
    illum::check_json_text(text, "t.json", 64);
  } catch (const illum::InputError& e) {
    return e.what();
  }
  return "";
}

// Two quads facing each other, 100 × 100; `floor` is the floor's vertices.
std::string two_quads(const std::string& floor) {
  return R"({"format": 1,
             "camera": {"eye": [50, 50, -200], "target": [50, 50, 50], "up": [0, 1, 0],
                        "vertical_fov_degrees": 40, "width": 8, "height": 8},
             "materials": {"w": {"diffuse": [0.5, 0.5, 0.5]},
                           "l": {"diffuse": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
             "primitives": [{"type": "polygon", "material": "w", "vertices": )" +
         floor + R"(},
                            {"type": "polygon", "material": "l",
                             "vertices": [[0, 100, 0], [100, 100, 0], [100, 100, 100], [0, 100, 100]]}]})";
}

// f(s) = s − root: one sign change, at `root`.
struct Line : illum::RealFunction {
  double root;
  explicit Line(double r) : root(r) {}
  double value(double s) const override { return s - root; }
  double derivative(double) const override { return 1.0; }
};

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("hard case: a march far from the origin ends although s + step rounds back to s") {
    // At 1e17 a double's spacing is 16, so s + 1 == s: a loop that adds the
    // step until it reaches the end never ends. Counted steps do.
    const double lo = 1e17;
    const illum::Interval range(lo, lo + 1024);
    CHECK_FALSE(illum::march_for_sign_change(Line(-1.0), range, 1.0).has_value());
    const auto hit = illum::march_for_sign_change(Line(lo + 500), range, 1.0);
    REQUIRE(hit.has_value());
    CHECK(hit->lo <= lo + 500);
    CHECK(hit->hi >= lo + 500);
    // More steps than the stated maximum: refused at once, not marched.
    CHECK_THROWS_AS(illum::march_for_sign_change(Line(-1.0), illum::Interval(0.0, 1e6), 1e-3),
                    std::invalid_argument);
  }

  TEST_CASE("bad input: a rolled-back run leaves its output folder exactly as it was") {
    // Contract: while the run is open its files are staged (readable at staged_path),
    // the folder itself is untouched; roll_back removes the staging, the lock and the
    // folders it made, so the parent holds what it held before.
    const fs::path parent = fresh_folder("rollback");
    const fs::path dir = parent / "out";
    illum::write_text_file(dir / "old.txt", "old\n");
    {
      illum::WriteTransaction t(dir);
      illum::write_text_file(dir / "old.txt", "new\n");
      illum::write_text_file(dir / "sub" / "deeper" / "a.txt", "a\n");
      illum::write_text_file(dir / "b.txt", "b\n");
      CHECK(read(dir / "old.txt") == "old\n");  // not replaced before the commit
      CHECK(read(illum::staged_path(dir / "old.txt")) == "new\n");
      CHECK(fs::exists(illum::staged_path(dir / "sub" / "deeper" / "a.txt")));
      CHECK_FALSE(fs::exists(dir / "sub"));
      t.roll_back();
    }
    CHECK(read(dir / "old.txt") == "old\n");
    CHECK_FALSE(fs::exists(dir / "b.txt"));
    CHECK_FALSE(fs::exists(dir / "sub"));
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
    CHECK(entries == 1);  // old.txt alone: no temporary or moved-aside file
    entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(parent)) ++entries;
    CHECK(entries == 1);  // out alone: no staging folder, no lock file
    fs::remove_all(parent);
  }

  TEST_CASE("bad input: a committed run keeps its files and leaves no moved-aside copy") {
    const fs::path parent = fresh_folder("commit");
    const fs::path dir = parent / "out";
    illum::write_text_file(dir / "old.txt", "old\n");
    illum::write_text_file(dir / "kept.txt", "kept\n");
    {
      illum::WriteTransaction t(dir);
      illum::write_text_file(dir / "old.txt", "new\n");
      illum::write_text_file(dir / "c.txt", "c\n");
      t.commit();
    }
    CHECK(read(dir / "old.txt") == "new\n");
    CHECK(read(dir / "c.txt") == "c\n");
    CHECK(read(dir / "kept.txt") == "kept\n");  // a file the run did not write stays
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
    CHECK(entries == 3);
    entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(parent)) ++entries;
    CHECK(entries == 1);
    fs::remove_all(parent);
  }

  TEST_CASE("bad input: a file outside the output folder appears only at the commit") {
    const fs::path dir = fresh_folder("outside");
    {
      illum::WriteTransaction t(dir / "out");
      illum::write_text_file(dir / "extra.ply", "ply\n");
      CHECK_FALSE(fs::exists(dir / "extra.ply"));
      CHECK(read(illum::staged_path(dir / "extra.ply")) == "ply\n");
      t.roll_back();
    }
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
    CHECK(entries == 0);
    {
      illum::WriteTransaction t(dir / "out");
      illum::write_text_file(dir / "extra.ply", "ply\n");
      t.commit();
    }
    CHECK(read(dir / "extra.ply") == "ply\n");
    fs::remove_all(dir);
  }

  TEST_CASE("bad input: a folder where a file goes is an error, not replaced") {
    const fs::path dir = fresh_folder("blocker");
    fs::create_directories(dir / "x.png");
    ILLUM_CHECK_THROWS_CONTAINING(illum::write_text_file(dir / "x.png", "x"), "in the way",
                                  std::runtime_error);
    CHECK(fs::is_directory(dir / "x.png"));
    fs::remove_all(dir);
  }

  TEST_CASE("bad input: JSON nested deeper than the limit names the path, without recursion") {
    const std::string deep = std::string(1000000, '[') + std::string(1000000, ']');
    const std::string e = refusal(deep);
    CHECK(e.find("nested more than 64") != std::string::npos);
    CHECK(e.find("t.json") != std::string::npos);
    // 64 levels are allowed; brackets inside strings do not count.
    CHECK(refusal(std::string(64, '[') + std::string(64, ']')).empty());
    CHECK(refusal(std::string(65, '[') + std::string(65, ']')) != "");
    CHECK(refusal(R"({"a": ")" + std::string(1000, '[') + R"(\"[["})").empty());
  }

  TEST_CASE("bad input: a number beyond a double names its field and is quoted as written") {
    const std::string e = refusal(R"({"a": {"b": [1, 2e3, -1E+999]}})");
    CHECK(e.find("a.b[2]") != std::string::npos);
    CHECK(e.find("-1E+999") != std::string::npos);
    CHECK(refusal(R"({"a": 1.7e308, "b": 1e-999})").empty());  // the largest double; underflow is 0
    CHECK(refusal(R"({"x": 1, "y": [0, 1e999]})").find("y[1]") != std::string::npos);
  }

  TEST_CASE("bad input: path_problem names an empty path, a link loop and a dangling link, nothing else") {
    const fs::path d = fs::temp_directory_path() / ("illum_path_problem_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d / "real");
    fs::create_symlink("loop", d / "loop");
    fs::create_symlink("nowhere", d / "gone");
    fs::create_symlink("real", d / "good");
    CHECK(illum::path_problem("") == "the path is empty (name a file or folder; '.' is the current folder)");
    // std::string's own constructor first: GCC 12 warns a false -Wrestrict on "'" + std::string&&.
    const std::string loop = std::string("'") + (d / "loop").string() +
                             "' is a symbolic link that leads back to itself (a link loop)";
    CHECK(illum::path_problem(d / "loop") == loop);
    CHECK(illum::path_problem(d / "loop" / "sub") == loop);  // named at the link, not at the path's end
    CHECK(illum::path_problem(d / "gone") ==
          std::string("'") + (d / "gone").string() +
              "' is a symbolic link to 'nowhere', which does not exist (a dangling link)");
    CHECK(illum::path_problem(d / "good" / "new") == "");  // a link to a folder, then a name not made yet
    CHECK(illum::path_problem(d / "missing" / "deeper") == "");
    CHECK(illum::path_problem("cornell") == "");  // a shipped scene's name
    fs::remove_all(d);
  }

  TEST_CASE("nearest name: a typo is matched, an unrelated word is not") {
    CHECK(illum::nearest_name("emision", {"reflectance", "emission"}) == "emission");
    CHECK(illum::nearest_name("colour", {"name", "center", "radius", "color"}) == "color");
    CHECK(illum::nearest_name("banana", {"name", "center", "radius", "color"}).empty());
    CHECK(illum::edit_distance("kitten", "sitting") == 3);  // the textbook example
  }

  TEST_CASE("bad input: a nearly planar quad is refused with its field named, or meshed at every size") {
    // One planarity rule, applied at the loader: whatever it decides, no later
    // step (meshing, make_patch) may refuse what it accepted, and a refusal
    // names the vertices. h = 3.6e-4 puts each vertex h/4 = 9e-5 off the mean
    // plane: within the radiosity check's 1e-6 × 100 but beyond make_patch's
    // own 1e-6 × 70.7 for a single patch; h = 1e-12 is planar to rounding.
    for (const char* raised : {"0.00036", "1e-12"}) {
      const std::string text =
          two_quads(std::string("[[0, 0, 0], [0, 0, 100], [100, ") + raised + ", 100], [100, 0, 0]]");
      for (double edge : {200.0, 30.0}) {
        CAPTURE(raised);
        CAPTURE(edge);
        try {
          const illum::RadiosityScene s = illum::parse_radiosity_scene(text, "q.json", edge);
          double area = 0;
          for (std::size_t i = 0; i < s.surfaces[0].patch_count; ++i) area += s.patches[i].area;
          CHECK(area == doctest::Approx(1e4).epsilon(1e-6));
        } catch (const illum::InputError& e) {
          CHECK(e.field().find("primitives[0].vertices") == 0);
          CHECK(std::string(raised) != "1e-12");  // a planar quad must load
        }
      }
    }
  }

  TEST_CASE("bad input: a wall far larger than the patch edge is refused by count, at once") {
    const std::string text = two_quads("[[0, 0, 0], [0, 0, 1e9], [1e9, 0, 1e9], [1e9, 0, 0]]");
    try {
      (void)illum::parse_radiosity_scene(text, "wall.json", 1.0);
      FAIL("a 1e18-patch wall was accepted");
    } catch (const illum::InputError& e) {
      CHECK(e.field() == "primitives[0].vertices");
      CHECK(std::string(e.what()).find("1e+18") != std::string::npos);
    }
  }

  TEST_CASE("bad input: memory checks give what was asked and the limit") {
    CHECK_NOTHROW(illum::check_memory("a small table", 1000, 8));
    ILLUM_CHECK_THROWS_CONTAINING(illum::check_memory("a huge table", 1e12, 8), "would need 8000.0 GB",
                                  std::length_error);
  }
}
