// Command-line parsing for the tools with the exit status of Unix tools: 0 after --help or
// --version, 2 for a usage error (CLI11's own codes, 105 and up, mean nothing to a shell).
#ifndef M4D_TOOLS_USAGE_EXIT_H_
#define M4D_TOOLS_USAGE_EXIT_H_

#include <CLI/CLI.hpp>

#define M4D_PARSE_ARGUMENTS(app, argc, argv) \
  do {                                       \
    try {                                    \
      (app).parse((argc), (argv));           \
    } catch (const CLI::ParseError& e) {     \
      return (app).exit(e) == 0 ? 0 : 2;     \
    }                                        \
  } while (0)

#endif  // M4D_TOOLS_USAGE_EXIT_H_
