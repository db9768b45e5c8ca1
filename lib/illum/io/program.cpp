#include "illum/io/program.hpp"

#include <charconv>
#include <iostream>
#include <new>
#include <string_view>

#include <CLI/CLI.hpp>

#include "illum/core/atomic_file.hpp"
#include "illum/core/error.hpp"
#include "illum/core/platform.hpp"
#include "illum/core/threads.hpp"

namespace illum {

int run_program(int argc, char** argv, const ProgramInfo& info,
                const std::function<void(CLI::App&)>& add_options,
                const std::function<void(const ProgramOptions&)>& body) {
  CLI::App app(info.title + "\n\n" + info.description, info.id);
  ProgramOptions options;
  options.out = std::filesystem::path("out") / info.id;
  app.add_option("--out", options.out, "Folder for the outputs (images, tables, plots)")
      ->capture_default_str();
  // --quick is a plain switch: "--quick=3" is refused, not read as "true".
  app.add_flag("--quick", options.quick, "Small sizes and short studies (used by the tests)")
      ->disable_flag_override();
  // Read as text, so that "-1" is refused instead of wrapping to 2^64 - 1 and
  // 2^64 is refused instead of saturating.
  std::string seed_text = std::to_string(options.seed);
  app.add_option("--seed", seed_text, "Seed for every random choice (0 to 2^64 - 1)")
      ->capture_default_str()
      ->check(
          [&](const std::string& text) -> std::string {
            std::uint64_t value = 0;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, value);
            if (text.empty() || ec != std::errc() || ptr != end)
              return "must be a whole number from 0 to 18446744073709551615, got '" + text + "'";
            return "";
          },
          "SEED");
  const int cores = processor_count();
  app.add_option("--threads", options.threads,
                 "Threads to use (0 = all cores, at most " + std::to_string(max_threads) + ")")
      ->capture_default_str()
      ->check(CLI::Range(0, max_threads));
  bool print_timed_cores = false;
  app.add_flag("--timed-cores", print_timed_cores,
               "Print how many cores this program's timings use (one or all) and exit")
      ->disable_flag_override();
  if (add_options) add_options(app);
  if (const std::string refused = refuse_switch_values(argc, argv, app); !refused.empty()) {
    std::cerr << info.id << ": error: " << refused << "\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (print_timed_cores) {  // before any check of the machine or the output folder
    std::cout << (info.timed_cores == TimedCores::one ? "one" : "all") << "\n";
    return 0;
  }
  std::from_chars(seed_text.data(), seed_text.data() + seed_text.size(), options.seed);
  const ScopedThreadCount threads(options.threads);  // 0: every core, OpenMP's default
  if (options.threads > cores)
    std::cerr << info.id << ": note: --threads " << options.threads << " is more than this machine's "
              << cores << " cores\n";
  if (options.threads > 1 && !has_openmp)
    std::cerr << info.id
              << ": note: this build has no OpenMP (ILLUM_OPENMP): every loop runs on one thread\n";
  // Every file the body writes is staged (core/atomic_file): if it throws or a
  // signal stops it, the output folder is left as it was; commit() moves the
  // run's files in at the end (validate before write, by construction).
  WriteTransaction transaction(options.out, "--out", info.id);
  return run_in_transaction(info.id, transaction, [&] {
    check_output_folder(options.out, "--out");  // before any work: a file or a busy folder is refused now
    body(options);
  });
}

std::string refuse_switch_values(int argc, char** argv, const CLI::App& app) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--") break;
    const std::size_t equals = arg.find('=');
    if (arg.rfind("--", 0) != 0 || equals == std::string_view::npos) continue;
    const std::string name(arg.substr(2, equals - 2));
    const CLI::Option* option = app.get_option_no_throw("--" + name);
    if (option && option->get_expected_max() == 0)  // a switch: it takes no value
      return "--" + name + " is a switch and takes no value; got '" + std::string(arg) + "' (write --" +
             name + " alone)";
  }
  return "";
}

int run_in_transaction(const std::string& id, WriteTransaction& transaction,
                       const std::function<void()>& body) {
  try {
    body();
    transaction.commit();
  } catch (const NotImplemented& e) {
    transaction.roll_back();
    std::cerr << id << ": " << e.message() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    transaction.roll_back();
    std::cerr << id << ": error: out of memory (a request the memory checks did not foresee; "
              << "try smaller sizes); nothing was written\n";
    return 1;
  } catch (const std::exception& e) {
    transaction.roll_back();
    std::cerr << id << ": error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

void report_progress(const std::string& id, const std::string& what, int done, int total) {
  static const bool terminal = stderr_is_terminal();
  std::cerr << (terminal ? "\r" : "") << id << ": " << what << " " << done << "/" << total
            << (terminal && done < total ? "" : "\n") << std::flush;
}

}  // namespace illum
