// Command-line parsing for the tools with the exit status of Unix tools: 0 after --help or
// --version, 2 for a usage error (CLI11's own codes, 105 and up, mean nothing to a shell).
// Every tool answers --version the same way, and a tool run without the arguments it needs
// prints its usage rather than one line about the first missing one.
#ifndef M4D_TOOLS_USAGE_EXIT_H_
#define M4D_TOOLS_USAGE_EXIT_H_

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "tools/version_line.h"

namespace m4d {

// Whether a command cannot run without arguments: a required option or a subcommand.
inline bool NeedsArguments(const CLI::App& app) {
  if (app.get_require_subcommand_min() > 0 || app.get_require_option_min() > 0) return true;
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_required()) return true;
  }
  return false;
}

// The command a bare command line names: the tool itself, or a subcommand given alone.
inline CLI::App* BareCommand(CLI::App& app, int argc, char** argv) {
  if (argc <= 1) return &app;
  if (argc > 2) return nullptr;
  const std::string word = argv[1];
  const auto named =
      app.get_subcommands([&word](const CLI::App* command) { return command->check_name(word); });
  return named.empty() ? nullptr : named.front();
}

// Parses the command line; false when the tool must return *exit_code at once (0 after --help
// or --version, 2 for a usage error).
inline bool ParseArguments(CLI::App& app, int argc, char** argv, int* exit_code) {
  app.set_version_flag("--version", VersionLine(argv[0]));
  const std::string path = argv[0];
  if (app.get_name().empty()) app.name(path.substr(path.find_last_of('/') + 1));
  CLI::App* bare = BareCommand(app, argc, argv);
  if (bare != nullptr && NeedsArguments(*bare)) {
    std::fputs(bare->help().c_str(), stderr);
    *exit_code = 2;
    return false;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    *exit_code = app.exit(e) == 0 ? 0 : 2;
    return false;
  }
  return true;
}

}  // namespace m4d

#define M4D_PARSE_ARGUMENTS(app, argc, argv)                                 \
  do {                                                                       \
    int m4d_usage_exit_code = 0;                                             \
    if (!m4d::ParseArguments((app), (argc), (argv), &m4d_usage_exit_code)) { \
      return m4d_usage_exit_code;                                            \
    }                                                                        \
  } while (0)

#endif  // M4D_TOOLS_USAGE_EXIT_H_
