// Lesson 09: the radiosity equation and form factors.
// Checks B = πI, runs every form-factor method of the notes against the
// closed forms (error and time, log-log), and computes the full form-factor
// matrix of a closed cube meshed 12 × 12 per face (864 patches).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "illum/core/image.hpp"
#include "illum/core/random.hpp"
#include "illum/core/stopwatch.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"
#include "illum/radiosity/form_factor_contour.hpp"
#include "illum/radiosity/form_factor_hierarchical.hpp"
#include "illum/radiosity/form_factor_sampling.hpp"
#include "illum/radiosity/form_factor_scene.hpp"
#include "illum/radiosity/radiosity_equation.hpp"
#include "illum/radiosity/rectangle_form_factors.hpp"

using namespace illum;

namespace {

constexpr double pi = std::numbers::pi;

Patch floor_square() { return make_patch({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}); }
Patch ceiling_square() { return make_patch({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}); }
Patch wall_square() { return make_patch({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}); }

// Mean time of `run` (at least `min_seconds` of repetitions) and its last value.
double timed(const std::function<double()>& run, double& seconds, double min_seconds) {
  double value = 0;
  long calls = 0;
  Stopwatch watch;
  do {
    value = run();
    ++calls;
  } while (watch.seconds() < min_seconds);
  seconds = watch.seconds() / static_cast<double>(calls);
  return value;
}

void cube_figure(OutputFolder& out, int n, bool quick) {
  const std::vector<Patch> patches = mesh_cube_interior(n);
  const FormFactorMatrix exact = closed_form_rectangle_matrix(patches);
  Table table(
      {"method", "patches", "seconds", "max abs(F - F_exact)", "max abs(row sum - 1)", "reciprocity error"});
  struct Variant {
    std::string name;
    ContourOptions options;
    PairReuse reuse;
  };
  // The first row reuses the value of a pair for all its translates (lesson 09, §11); the others
  // call the contour integral for every pair i < j.
  for (const Variant& v :
       {Variant{"contour, closed-form edge pairs, translates reused", {}, PairReuse::translates},
        Variant{"contour, closed-form edge pairs, every pair", {}, PairReuse::none},
        Variant{"contour, plain Gauss-Legendre 8, every pair", {8, false, false}, PairReuse::none},
        Variant{"contour, plain Gauss-Legendre 16, every pair", {16, false, false}, PairReuse::none}}) {
    double best = 1e300;
    FormFactorMatrix f;
    for (int repeat = 0; repeat < (quick ? 1 : 5); ++repeat) {
      Stopwatch watch;
      f = contour_form_factor_matrix(patches, v.options, v.reuse);
      best = std::min(best, watch.seconds());
    }
    double worst = 0, row = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      row = std::max(row, std::abs(f.row_sum(i) - 1));
      for (std::size_t j = 0; j < patches.size(); ++j)
        worst = std::max(worst, std::abs(f(i, j) - exact(i, j)));
    }
    std::printf("cube %d x %d per face (%zu patches), %s: %.3f s, max error %.3g, max |row sum - 1| %.3g\n",
                n, n, patches.size(), v.name.c_str(), best, worst, row);
    table.add_row(
        {v.name, static_cast<std::int64_t>(patches.size()), best, worst, row, reciprocity_error(f, patches)});
  }
  out.table(table, "cube_matrix",
            "Form-factor matrix of the closed cube by the double contour integral (OpenMP, i < j plus "
            "reciprocity; 'translates reused' computes each class of translated pairs once), "
            "best of 5 runs, against the closed forms for rectangles");
  // The matrix as an image: log10 F on a viridis scale (white-free, black = 0).
  const int size = static_cast<int>(patches.size());
  Image image(size, size);
  const FormFactorMatrix f = contour_form_factor_matrix(patches, {}, PairReuse::translates);
  for (int i = 0; i < size; ++i)
    for (int j = 0; j < size; ++j) {
      const double value = f(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
      image.at(j, i) =
          value > 0 ? colormap_viridis(std::clamp((std::log10(value) + 6) / 5, 0.0, 1.0)) : Color(0.0);
    }
  out.image(image, "cube_matrix",
            "F_ij of the cube's inside, rows i and columns j by face (x=0, x=1, y=0, y=1, z=0, z=1); colour "
            "log10 F "
            "from -6 to -1, black where F = 0 (coplanar patches)");
}

}  // namespace

int main(int argc, char** argv) {
  const ProgramInfo info{
      "lesson09", "The radiosity equation and form factors",
      "Checks B = pi I, measures every form-factor method against closed forms (error vs time), "
      "and computes the cube's 864-patch form-factor matrix."};
  bool cube_only = false;
  int cube_n = 12;
  return run_program(
      argc, argv, info,
      [&](CLI::App& app) {
        app.add_flag("--cube-only", cube_only, "only the cube figure (timing of the 864-patch matrix)");
        // 24: 3,456 patches, 12 million pairs per matrix and minutes per variant; beyond, hours.
        app.add_option("--cube-n", cube_n, "patches per cube edge (default 12, at most 24)")
            ->check(CLI::Range(1, 24));
      },
      [&](const ProgramOptions& options) {
        OutputFolder out(options.out, info.id, info.title);
        if (cube_only) {
          cube_figure(out, cube_n, false);
          out.finish();
          return;
        }
        const bool quick = options.quick;
        const double min_time = quick ? 0.0 : 0.02;

        // --- B = πI ------------------------------------------------------------
        Table exitance({"method", "knob", "B", "abs(B - pi I)"});
        const double radiance = 1.0;
        auto lambertian = [&](double, double) { return radiance; };
        for (int n : {1, 2, 3, 4, 6, 8}) {
          const double b = exitance_from_radiance_quadrature(lambertian, n);
          exitance.add_row(
              {"Gauss-Legendre n x n", static_cast<std::int64_t>(n), b, std::abs(b - pi * radiance)});
        }
        for (int samples : {100, 10000, 1000000}) {
          if (quick && samples > 10000) continue;
          Rng rng(options.seed);
          const double b = exitance_from_radiance_monte_carlo(lambertian, samples, rng);
          exitance.add_row(
              {"Monte Carlo, N samples", static_cast<std::int64_t>(samples), b, std::abs(b - pi * radiance)});
        }
        out.table(exitance, "b_equals_pi_i", "B = integral of I cos(phi) over the hemisphere, for I = 1: pi",
                  6);

        // --- the study: error against closed forms vs time, every method ---------
        Table study({"method", "case", "knob", "error", "seconds"});
        const Patch floor = floor_square(), ceiling = ceiling_square(), wall = wall_square();
        const double parallel_exact = axis_aligned_rectangles_form_factor(floor, ceiling);  // C-11: 0.19982
        const double shared_exact = axis_aligned_rectangles_form_factor(floor, wall);       // C-14: 0.20004
        struct Pair {
          std::string name;
          const Patch* to;
          double exact;
        };
        const Pair pairs[2] = {{"parallel squares", &ceiling, parallel_exact},
                               {"shared edge", &wall, shared_exact}};
        for (const Pair& pair : pairs) {
          double seconds = 0;
          double f = timed([&] { return polygon_polygon_form_factor(floor, *pair.to); }, seconds, min_time);
          study.add_row({"contour (closed-form edge pairs)", pair.name, std::int64_t{0},
                         std::max(std::abs(f - pair.exact), 1e-17), seconds});
          for (int order : {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64}) {
            const ContourOptions plain{order, false, false};
            f = timed([&] { return polygon_polygon_form_factor(floor, *pair.to, plain); }, seconds, min_time);
            study.add_row({"contour (plain Gauss-Legendre)", pair.name, static_cast<std::int64_t>(order),
                           std::max(std::abs(f - pair.exact), 1e-17), seconds});
          }
          for (double tolerance : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
            if (quick && tolerance < 1e-4) continue;
            f = timed([&] { return form_factor_hierarchical(floor, *pair.to, tolerance).value; }, seconds,
                      min_time);
            study.add_row({"hierarchical", pair.name, tolerance, std::abs(f - pair.exact), seconds});
          }
          // Monte Carlo: the RMS error over 8 seeds, so that the N^-1/2 line is not a single noisy draw.
          for (int samples = 100; samples <= (quick ? 10000 : 1000000); samples *= 10) {
            double squared = 0;
            Stopwatch watch;
            for (int seed = 0; seed < 8; ++seed) {
              Rng rng(options.seed + static_cast<std::uint64_t>(seed));
              const double e = form_factor_monte_carlo(floor, *pair.to, {}, samples, rng) - pair.exact;
              squared += e * e;
            }
            study.add_row({"Monte Carlo area to area", pair.name, static_cast<std::int64_t>(samples),
                           std::sqrt(squared / 8), watch.seconds() / 8});
          }
          report_progress(info.id, "study " + pair.name, 1, 1);
        }
        // Point to polygon: the receiver under a corner of the unit square at height 1 (B-3).
        const Point3 x(0, 0, 0);
        const Vec3 up(0, 0, 1);
        const double corner_exact = (2 * (1 / std::sqrt(2.0)) * std::atan(1 / std::sqrt(2.0))) /
                                    (2 * pi);  // Howell B-3, a = b = c = 1
        {
          double seconds = 0;
          const double f =
              timed([&] { return point_polygon_form_factor(x, up, ceiling); }, seconds, min_time);
          study.add_row({"point: contour formula", "corner", std::int64_t{0},
                         std::max(std::abs(f - corner_exact), 1e-17), seconds});
          for (int segments : {1, 2, 4, 8, 16, 32, 64, 128, 256}) {
            const double g =
                timed([&] { return form_factor_nusselt(x, up, ceiling, segments); }, seconds, min_time);
            study.add_row({"point: Nusselt projected area", "corner", static_cast<std::int64_t>(segments),
                           std::abs(g - corner_exact), seconds});
          }
          using Estimator = std::function<double(int, Rng&)>;
          const std::pair<std::string, Estimator> estimators[3] = {
              {"point: area sampling",
               [&](int n, Rng& rng) { return form_factor_area_sampling(x, up, ceiling, {}, n, rng); }},
              {"point: hemisphere uniform",
               [&](int n, Rng& rng) { return form_factor_hemisphere_uniform(x, up, ceiling, {}, n, rng); }},
              {"point: hemisphere cosine",
               [&](int n, Rng& rng) { return form_factor_hemisphere_cosine(x, up, ceiling, {}, n, rng); }}};
          for (const auto& [name, estimate] : estimators)
            for (int samples = 100; samples <= (quick ? 10000 : 1000000); samples *= 10) {
              double squared = 0;
              Stopwatch watch;
              for (int seed = 0; seed < 8; ++seed) {
                Rng rng(options.seed + static_cast<std::uint64_t>(seed));
                const double e = estimate(samples, rng) - corner_exact;
                squared += e * e;
              }
              study.add_row({name, "corner", static_cast<std::int64_t>(samples), std::sqrt(squared / 8),
                             watch.seconds() / 8});
            }
        }
        out.table(
            study, "study",
            "Error against the closed forms (C-11 parallel squares, C-14 squares sharing an edge, B-3 point "
            "under a corner) and time per estimate; Monte Carlo errors are RMS over 8 seeds");
        PlotSpec by_time{
            "Form factors: error vs time", "seconds per estimate", "|error|", true, true, {}, 1000, 620};
        const char* methods[] = {"contour (plain Gauss-Legendre)", "hierarchical",
                                 "Monte Carlo area to area"};
        for (const char* m : methods)
          for (const char* c : {"parallel squares", "shared edge"})
            by_time.series.push_back({"study.csv", 5, 4, std::string(m) + ", " + c,
                                      "strcol(1) eq '" + std::string(m) + "' && strcol(2) eq '" + c + "'"});
        for (const char* m : {"point: Nusselt projected area", "point: area sampling",
                              "point: hemisphere uniform", "point: hemisphere cosine"})
          by_time.series.push_back({"study.csv", 5, 4, m, "strcol(1) eq '" + std::string(m) + "'"});
        out.plot(
            by_time, "study_error_vs_time",
            "Error vs time, log-log: Monte Carlo falls as N^-1/2, quadrature and hierarchical faster; the "
            "shared edge slows plain Gauss-Legendre to an algebraic rate");
        PlotSpec by_knob{"Form factors: error vs accuracy knob",
                         "knob (points, samples, segments)",
                         "|error|",
                         true,
                         true,
                         {},
                         1000,
                         620};
        for (const char* m : {"contour (plain Gauss-Legendre)", "Monte Carlo area to area"})
          for (const char* c : {"parallel squares", "shared edge"})
            by_knob.series.push_back({"study.csv", 3, 4, std::string(m) + ", " + c,
                                      "strcol(1) eq '" + std::string(m) + "' && strcol(2) eq '" + c + "'"});
        for (const char* m : {"point: Nusselt projected area", "point: hemisphere cosine"})
          by_knob.series.push_back({"study.csv", 3, 4, m, "strcol(1) eq '" + std::string(m) + "'"});
        out.plot(by_knob, "study_error_vs_knob", "Error vs the accuracy knob of each method, log-log");

        // --- the cube figure -------------------------------------------------------
        cube_figure(out, quick ? 4 : cube_n, quick);
        out.finish();
      });
}
