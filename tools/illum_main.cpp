// The `illum` command line. It grows with the lessons: each adds a subcommand.
#include <iostream>

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app("illum: global illumination, step by step. Each lesson adds commands.", "illum");
  app.require_subcommand(0, 1);
  auto* version = app.add_subcommand("version", "Print the version");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (version->parsed() || app.get_subcommands().empty()) std::cout << "illum 0.1.0\n";
  return 0;
}
