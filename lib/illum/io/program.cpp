#include "illum/io/program.hpp"

#include <iostream>

#include <omp.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include "illum/core/error.hpp"

namespace illum {

int run_program(int argc, char** argv, const ProgramInfo& info,
                const std::function<void(CLI::App&)>& add_options,
                const std::function<void(const ProgramOptions&)>& body) {
  CLI::App app(info.title + "\n\n" + info.description, info.id);
  ProgramOptions options;
  options.out = std::filesystem::path("out") / info.id;
  app.add_option("--out", options.out, "Folder for the outputs (images, tables, plots)")
      ->capture_default_str();
  app.add_flag("--quick", options.quick, "Small sizes and short studies (used by the tests)");
  app.add_option("--seed", options.seed, "Seed for every random choice")->capture_default_str();
  app.add_option("--threads", options.threads, "Threads to use (0 = all cores)")->capture_default_str();
  if (add_options) add_options(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (options.threads > 0) omp_set_num_threads(options.threads);
  try {
    body(options);
  } catch (const NotImplemented& e) {
    std::cerr << info.id << ": " << e.message() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << info.id << ": error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

void report_progress(const std::string& id, const std::string& what, int done, int total) {
  static const bool terminal = ::isatty(2) != 0;
  std::cerr << (terminal ? "\r" : "") << id << ": " << what << " " << done << "/" << total
            << (terminal && done < total ? "" : "\n") << std::flush;
}

}  // namespace illum
