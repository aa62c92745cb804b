// Splitting dwtool's command line with CLI11: subcommands forward and inverse, shared options.
#pragma once

#include <optional>

#include "request.h"
#include "wavelet_commands.h"

namespace dwtool {

struct ParsedCommandLine {
  std::optional<RawOptions> options;  // forward or inverse
  std::optional<AppOptions> app;      // edit, combine, decouple or deform; both empty: exit with exit_code
  int exit_code = 0;
};

// --help prints to stdout and gives exit code 0; a usage error prints one "dwtool: " line to stderr
// and gives exit code 2 (runtime failures, found later, use 1).
ParsedCommandLine parse_command_line(int argc, char** argv);

}  // namespace dwtool
