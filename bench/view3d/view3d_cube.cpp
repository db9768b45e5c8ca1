// Lesson 09: illum's form-factor matrix beside NIST View3D, on the same closed cube.
//
//   build/release/bin/bench_view3d_cube --view3d PATH/TO/View3D [--out DIR]   (bench/README.md)
//
// View3D is not part of illum: bench/README.md says how to build it from its public source. For
// each cube (12, 20 and 30 patches per edge: 864, 2,400 and 5,400 patches, mesh_cube_interior) the
// program writes the mesh as View3D's input (.vs3, every surface a quadrilateral, no enclosure
// adjustment: encl=0), then, in turn, runs View3D on it (its output flushed to the disk before going
// on: sync) and computes illum's matrix (contour_form_factor_matrix to the same tolerance, one
// thread), several times. It reports:
//   * the seconds each spent computing the matrix: illum's thread CPU time around the call
//     (allocating the matrix included), View3D's own CPU timer ("seconds to compute view factors"
//     in its log: its allocation and its output file are outside it); the mean of the runs for each
//     (View3D prints its time to 0.01 s, and the mean of such readings, unlike their median, is not
//     held to that step: 0.04 s is a third of the 864-patch cube's), their ratio, and the slowest
//     run of each;
//   * View3D's seconds to the matrix in memory, as illum's count it: its "seconds for all
//     calculations" less its "seconds to write view factors" (reading the input and allocating and
//     zeroing its half matrix included; a fresh page's first touch costs more in a virtual machine
//     than on bare metal, and illum's timer holds it), and illum's ratio to that;
//   * the largest error of each matrix against the closed forms for rectangles (View3D's from the
//     matrix it writes, to six decimals: its rounding, up to 5·10⁻⁷, is part of its error).
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "illum/core/thread_cpu_stopwatch.hpp"
#include "illum/core/threads.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/table.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/system/child_process.hpp"

namespace {

using namespace illum;

// The cube as View3D's input: one vertex per distinct point, one quadrilateral per patch with the
// patch's vertex order (View3D's active side is the right-hand rule's, as illum's normal is).
std::string vs3_text(const std::vector<Patch>& patches, int n, double tolerance) {
  std::vector<Point3> points;
  std::map<std::array<double, 3>, std::size_t> number;  // a point's number in `points`, from 1
  std::ostringstream surfaces;
  char buffer[128];
  for (std::size_t k = 0; k < patches.size(); ++k) {
    surfaces << "S " << k + 1;
    for (const Point3& v : patches[k].vertices) {
      const auto [at, added] = number.try_emplace({v.x, v.y, v.z}, points.size() + 1);
      if (added) points.push_back(v);
      surfaces << ' ' << at->second;
    }
    surfaces << " 0 0 0.5 s" << k + 1 << '\n';
  }
  std::ostringstream text;
  std::snprintf(buffer, sizeof buffer, "C encl=0 list=0 eps=%.17g\n", tolerance);
  text << "T closed cube, " << n << " patches per edge (illum's mesh_cube_interior)\n" << buffer << "F 3\n";
  for (std::size_t k = 0; k < points.size(); ++k) {
    std::snprintf(buffer, sizeof buffer, "V %zu %.17g %.17g %.17g\n", k + 1, points[k].x, points[k].y,
                  points[k].z);
    text << buffer;
  }
  text << surfaces.str() << "End of data\n";
  return text.str();
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The seconds of View3D's log line "  0.25 seconds <what>".
double logged_seconds(const std::string& text, const std::filesystem::path& log, const std::string& what) {
  const std::size_t at = text.rfind(" seconds " + what);
  if (at == std::string::npos) throw std::runtime_error(log.string() + " has no 'seconds " + what + "'");
  std::size_t begin = text.rfind('\n', at);
  begin = begin == std::string::npos ? 0 : begin + 1;
  return std::stod(text.substr(begin, at - begin));
}

struct View3dSeconds {
  double compute = 0;  // its view factors alone
  double matrix = 0;   // the matrix in memory: everything but writing it (input, allocation included)
};

View3dSeconds view3d_seconds(const std::filesystem::path& log) {
  const std::string text = read_file(log);
  return {
      logged_seconds(text, log, "to compute view factors"),
      logged_seconds(text, log, "for all calculations") - logged_seconds(text, log, "to write view factors")};
}

// The largest |F − exact| of View3D's output matrix: a header line, the areas' line, then n rows of
// n factors (row i: F_i0 … F_i(n−1)), each printed with six decimals.
double view3d_error(const std::filesystem::path& output, const FormFactorMatrix& exact) {
  const std::string text = read_file(output);
  const std::size_t areas = text.find('\n'), factors = text.find('\n', areas + 1);
  if (factors == std::string::npos)
    throw std::runtime_error(output.string() + ": no factors after the areas");
  const char* p = text.data() + factors + 1;
  const char* end = text.data() + text.size();
  double worst = 0;
  for (std::size_t i = 0; i < exact.size(); ++i)
    for (std::size_t j = 0; j < exact.size(); ++j) {
      while (p < end && (*p == ' ' || *p == '\n' || *p == '\r')) ++p;
      double f = 0;
      const auto [next, error] = std::from_chars(p, end, f);
      if (error != std::errc())
        throw std::runtime_error(output.string() + ": fewer factors than patches squared");
      p = next;
      worst = std::max(worst, std::abs(f - exact(i, j)));
    }
  return worst;
}

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (const double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

double largest_error(const FormFactorMatrix& f, const FormFactorMatrix& exact) {
  double worst = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = 0; j < f.size(); ++j) worst = std::max(worst, std::abs(f(i, j) - exact(i, j)));
  return worst;
}

int usage(const char* program, const std::string& problem) {
  std::fprintf(stderr,
               "bench_view3d_cube: %s\nusage: %s --view3d PATH [--tolerance T] [--sizes 12,20,30] [--runs N] "
               "[--work DIR] [--out DIR]\n",
               problem.c_str(), program);
  return 2;
}

struct Options {
  std::string view3d, out_dir, work_dir;
  double tolerance = 1e-4;
  std::vector<int> sizes = {12, 20, 30};
  int runs = 9;
};

// The command line into `o`; an empty string, or what is wrong with it.
std::string parse_options(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    if (i + 1 >= argc || argv[i + 1][0] == '\0') return "missing value for '" + option + "'";
    const std::string value = argv[++i];
    try {
      std::size_t used = 0;
      if (option == "--view3d") {
        o.view3d = value;
      } else if (option == "--out") {
        o.out_dir = value;
      } else if (option == "--work") {
        o.work_dir = value;
      } else if (option == "--tolerance") {
        o.tolerance = std::stod(value, &used);
        if (used != value.size() || !(o.tolerance >= 1e-15 && o.tolerance <= 1))
          throw std::invalid_argument("");
      } else if (option == "--runs") {
        o.runs = std::stoi(value, &used);
        if (used != value.size() || o.runs < 1 || o.runs > 100) throw std::invalid_argument("");
      } else if (option == "--sizes") {
        o.sizes.clear();
        std::stringstream list(value);
        for (std::string item; std::getline(list, item, ',');) {
          o.sizes.push_back(std::stoi(item, &used));
          if (used != item.size() || o.sizes.back() < 1 || o.sizes.back() > 60)
            throw std::invalid_argument("");
        }
        if (o.sizes.empty()) throw std::invalid_argument("");
      } else {
        return "unknown option '" + option + "'";
      }
    } catch (const std::exception&) {
      return "bad value for " + option + ": '" + value +
             "' (--tolerance in [1e-15, 1], --runs 1...100, --sizes n,n,... each 1...60)";
    }
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const std::string problem = parse_options(argc, argv, options); !problem.empty())
    return usage(argv[0], problem);
  const auto& [view3d, out_dir, work_dir, tolerance, sizes, runs] = options;
  if (view3d.empty()) return usage(argv[0], "--view3d is required (the View3D program to compare with)");
  const std::filesystem::path program = std::filesystem::absolute(view3d);
  if (!std::filesystem::is_regular_file(program)) return usage(argv[0], "no such program: '" + view3d + "'");
  const std::filesystem::path work = work_dir.empty()
                                         ? std::filesystem::temp_directory_path() / "illum_view3d_cube"
                                         : std::filesystem::path(work_dir);
  std::filesystem::create_directories(work);

  std::printf(
      "one thread; seconds: mean of %d runs, the two in turn (illum: thread CPU time of "
      "contour_form_factor_matrix, allocation included; View3D: its own 'seconds to compute view factors', "
      "to 0.01 s, allocation excluded), and the slowest run; 'to matrix': View3D's 'seconds for all "
      "calculations' less its 'seconds to write view factors' (input and allocation included)\n",
      runs);
  std::printf("%8s %10s | %10s %10s %6s | %10s %10s | %10s %6s | %12s %12s\n", "patches", "tolerance",
              "illum s", "View3D s", "ratio", "illum max", "View3D max", "to matrix", "ratio", "illum error",
              "View3D error");
  Table table({"patches", "tolerance", "illum seconds", "View3D seconds", "ratio", "illum slowest",
               "View3D slowest", "View3D seconds to the matrix", "ratio to it", "illum max abs(F - F_exact)",
               "View3D max abs(F - F_exact)"});
  for (const int n : sizes) {
    const std::vector<Patch> patches = mesh_cube_interior(n);
    const FormFactorMatrix exact = closed_form_rectangle_matrix(patches);
    const std::string name = "cube" + std::to_string(n);
    {
      std::ofstream input(work / (name + ".vs3"));
      input << vs3_text(patches, n, tolerance);
      if (!input) throw std::runtime_error("cannot write " + (work / (name + ".vs3")).string());
    }
    std::vector<double> illum_seconds, view3d_times, view3d_matrix_times;
    double illum_error = 0;
    for (int k = 0; k < runs; ++k) {
      const ToolRun run = run_tool({program.string(), name + ".vs3", name + ".out"}, work);
      if (!run.succeeded()) throw std::runtime_error("View3D failed on " + name + ".vs3: " + run.failure());
      // View3D's output (263 MB for the 5,400-patch cube) is still being written back to the disk when
      // it exits; left to run during illum's call, that write-back made it up to half again slower.
      sync();
      const View3dSeconds logged = view3d_seconds(work / "View3D.log");
      view3d_times.push_back(logged.compute);
      view3d_matrix_times.push_back(logged.matrix);
      const ScopedThreadCount one(1);
      ThreadCpuStopwatch watch;
      const FormFactorMatrix f = contour_form_factor_matrix(patches, FormFactorTolerance{tolerance});
      illum_seconds.push_back(watch.seconds());
      if (k == 0) illum_error = largest_error(f, exact);
    }
    const double view3d_error_value = view3d_error(work / (name + ".out"), exact);
    std::filesystem::remove(work / (name + ".out"));  // 263 MB for the 5,400-patch cube
    const double a = mean(illum_seconds), b = mean(view3d_times), c = mean(view3d_matrix_times);
    const double a_max = *std::max_element(illum_seconds.begin(), illum_seconds.end()),
                 b_max = *std::max_element(view3d_times.begin(), view3d_times.end());
    std::printf("%8zu %10.0e | %10.4f %10.4f %6.3f | %10.4f %10.2f | %10.4f %6.3f | %12.3g %12.3g\n",
                patches.size(), tolerance, a, b, a / b, a_max, b_max, c, a / c, illum_error,
                view3d_error_value);
    table.add_row({static_cast<std::int64_t>(patches.size()), tolerance, a, b, a / b, a_max, b_max, c, a / c,
                   illum_error, view3d_error_value});
  }
  if (!out_dir.empty()) {
    OutputFolder out(out_dir, "bench_view3d", "illum's form-factor matrix beside NIST View3D");
    out.table(table, "view3d_cube",
              "The closed cube's form-factor matrix, illum beside View3D at one tolerance, one thread, means",
              3);
    out.finish();
    std::printf("wrote %s/view3d_cube.md\n", out_dir.c_str());
  }
  return 0;
}
