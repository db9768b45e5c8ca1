#include "illum/io/program.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#include <string_view>

#include <CLI/CLI.hpp>

#include "illum/core/error.hpp"
#include "illum/core/threads.hpp"
#include "illum/io/whole_machine.hpp"
#include "illum/system/atomic_file.hpp"
#include "illum/system/charconv.hpp"
#include "illum/system/platform.hpp"

namespace illum {

const char* to_string(TimedCores cores) {
  switch (cores) {
    case TimedCores::one:
      return "one";
    case TimedCores::mixed:
      return "mixed";
    case TimedCores::all:
      return "all";
  }
  return "?";
}

int run_program(int argc, char** argv, const ProgramInfo& info,
                const std::function<void(CommandLine&)>& add_options,
                const std::function<void(const ProgramOptions&)>& body) {
  CLI::App app(info.title + "\n\n" + info.description, info.id);
  ProgramOptions options;
  options.out = std::filesystem::path("out") / info.id;
  app.add_option("--out", options.out, "Folder for the outputs (images, tables, plots)")
      ->capture_default_str()
      ->check(path_value().validator());
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
               "Print how many cores this program's timings use (one, mixed or all) and exit")
      ->disable_flag_override();
  if (add_options) {
    CommandLine command_line(app);
    add_options(command_line);
  }
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
    std::cout << to_string(info.timed_cores) << "\n";
    return 0;
  }
  // A malformed ILLUM_MAIN_JOB_FDS is refused before any work, not at the first WholeMachine.
  try {
    main_job_link();
  } catch (const std::exception& e) {
    std::cerr << info.id << ": error: " << e.what() << "\n";
    return 1;
  }
  std::from_chars(seed_text.data(), seed_text.data() + seed_text.size(), options.seed);
  const ScopedThreadCount threads(options.threads);  // 0: every core, OpenMP's default
  if (options.threads > cores)
    std::cerr << info.id << ": note: --threads " << options.threads << " is more than this machine's "
              << cores << " cores\n";
  if (options.threads > 1 && !has_openmp)
    std::cerr << info.id
              << ": note: this build has no OpenMP (ILLUM_OPENMP): every loop runs on one thread\n";
  // Every file the body writes is staged (system/atomic_file): if it throws or a
  // signal stops it, the output folder is left as it was; commit() moves the
  // run's files in at the end (validate before write, by construction).
  WriteTransaction transaction(options.out, "--out", info.id);
  return run_in_transaction(info.id, transaction, [&] {
    check_output_folder(options.out, "--out");  // before any work: a file or a busy folder is refused now
    remove_stale_run_files_noting(info.id, options.out, "--out");
    body(options);
  });
}

std::string path_problem(const std::filesystem::path& path) {
  if (path.empty()) return "the path is empty (name a file or folder; '.' is the current folder)";
  // Each step of the path in turn, so that the message names the link that is wrong.
  std::filesystem::path step;
  for (const std::filesystem::path& part : path) {
    step /= part;
    std::error_code ec;
    const std::filesystem::file_status link = std::filesystem::symlink_status(step, ec);
    if (ec || !std::filesystem::exists(link)) return "";  // missing from here on: its user says what it needs
    if (!std::filesystem::is_symlink(link)) continue;
    (void)std::filesystem::status(step, ec);  // only whether the link can be followed
    if (!ec) continue;
    const int e = ec.value();  // the system category's value is the errno of stat(2)
    const std::string what = "'" + step.string() + "' is a symbolic link";
    if (e == ELOOP) return what + " that leads back to itself (a link loop)";
    const std::filesystem::path target = std::filesystem::read_symlink(step, ec);
    if (e == ENOENT) return what + " to '" + target.string() + "', which does not exist (a dangling link)";
    return what + " that cannot be followed: " + std::strerror(e);
  }
  return "";
}

ValueCheck path_value() {
  return ValueCheck([](std::string& text) { return path_problem(text); }, "PATH");
}

void remove_stale_run_files_noting(const std::string& id, const std::filesystem::path& folder,
                                   const std::string& option) {
  for (const std::string& note : remove_stale_run_files(folder, option))
    std::cerr << id << ": note: " << note << "\n";
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

// --- a program's own options -------------------------------------------------------

ValueCheck::ValueCheck(std::function<std::string(std::string&)> test, const std::string& name)
    : validator_(std::make_shared<const CLI::Validator>(std::move(test), name)) {}

ValueCheck::ValueCheck(std::shared_ptr<const CLI::Validator> validator) : validator_(std::move(validator)) {}

ValueCheck operator&(const ValueCheck& first, const ValueCheck& second) {
  return ValueCheck(std::make_shared<const CLI::Validator>(first.validator() & second.validator()));
}

ValueCheck range(int lo, int hi) {
  return ValueCheck(std::make_shared<const CLI::Validator>(CLI::Range(lo, hi)));
}

ValueCheck range(double lo, double hi) {
  return ValueCheck(std::make_shared<const CLI::Validator>(CLI::Range(lo, hi)));
}

ValueCheck one_of(const std::vector<std::string>& names) {
  return ValueCheck(std::make_shared<const CLI::Validator>(CLI::IsMember(names)));
}

std::string bound_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

ValueCheck number_range(double lo, double hi) {
  return ValueCheck(
      [lo, hi](std::string& s) -> std::string {
        double value = 0;
        const auto [end, error] = from_chars_double(s.data(), s.data() + s.size(), value);
        if (s.empty() || error != std::errc() || end != s.data() + s.size() || !std::isfinite(value))
          return "'" + s + "' is not a finite number";
        if (!(value >= lo && value <= hi))
          return "Value " + s + " not in range " + bound_text(lo) + " to " + bound_text(hi);
        return "";
      },
      "NUMBER in [" + bound_text(lo) + ", " + bound_text(hi) + "]");
}

// The CLI11 option behind `option`; an Option() that names none is a programming error.
CLI::Option& Option::cli(const Option& option, const char* what) {
  require(option.option_ != nullptr, what);
  return *option.option_;
}

Option& Option::check(const ValueCheck& check) {
  cli(*this, "Option::check: the Option names no option (add it with CommandLine::add first)")
      .check(check.validator());
  return *this;
}

Option& Option::expected(int count) {
  cli(*this, "Option::expected: the Option names no option").expected(count);
  return *this;
}

Option& Option::show_default() {
  cli(*this, "Option::show_default: the Option names no option").capture_default_str();
  return *this;
}

Option& Option::excludes(const Option& other) {
  cli(*this, "Option::excludes: the Option names no option")
      .excludes(&cli(other, "Option::excludes: the other Option names no option"));
  return *this;
}

bool Option::given() const { return option_ != nullptr && option_->count() > 0; }

Option CommandLine::add(const std::string& name, int& value, const std::string& help) {
  return Option(app_->add_option(name, value, help));
}

Option CommandLine::add(const std::string& name, double& value, const std::string& help) {
  return Option(app_->add_option(name, value, help));
}

Option CommandLine::add(const std::string& name, std::string& value, const std::string& help) {
  return Option(app_->add_option(name, value, help));
}

Option CommandLine::add(const std::string& name, std::filesystem::path& value, const std::string& help) {
  return Option(app_->add_option(name, value, help));
}

Option CommandLine::add(const std::string& name, std::vector<int>& values, const std::string& help) {
  return Option(app_->add_option(name, values, help));
}

Option CommandLine::add(const std::string& name, std::vector<std::string>& values, const std::string& help) {
  return Option(app_->add_option(name, values, help));
}

Option CommandLine::add_flag(const std::string& name, bool& value, const std::string& help) {
  return Option(app_->add_flag(name, value, help));
}

void CommandLine::exclude_quick(std::initializer_list<Option> options) {
  for (const Option& o : options) Option::cli(o, "CommandLine::exclude_quick: an Option names no option");
  CLI::Option* quick = app_->get_option_no_throw("--quick");
  if (!quick) return;
  for (const Option& o : options) Option::cli(o, "").excludes(quick);
}

}  // namespace illum
