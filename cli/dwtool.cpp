// dwtool: one 2-D discrete wavelet transform of the gpuj2k engine, from file to file, so that the
// engine can be checked from outside (scripts, other implementations, the test suite).
//
//   dwtool forward -i image.png -o coeffs.pfm --kernel 97 --levels 5 --backend gpu
//   dwtool inverse -i coeffs.pfm -o image.png --kernel 97 --levels 5
//   dwtool edit -i in.png -o out.png --space ycc --band Y:1:*=1.8 --backend gpu   (and combine,
//   decouple, deform: the wavelet applications of thesis 4.7, cli/wavelet_commands.h)
//
// Any failure prints exactly one line "dwtool: ..." on stderr and exits with 1 (2 for usage
// errors); no output file is left behind, since it is only written, atomically, after success.

#include <exception>
#include <iostream>

#include "command_line.h"
#include "base/one_line.h"
#include "request.h"
#include "transform.h"

int main(int argc, char** argv) {
  constexpr int kRuntimeExitCode = 1;
  try {
    const dwtool::ParsedCommandLine parsed = dwtool::parse_command_line(argc, argv);
    if (parsed.app) {
      dwtool::run_app(*parsed.app);
      return 0;
    }
    if (!parsed.options) return parsed.exit_code;
    dwtool::run(dwtool::resolve(*parsed.options));
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "dwtool: " << base::one_line(e.what()) << '\n';
  } catch (...) {
    // Nothing may escape main: an uncaught exception would abort with a multi-line report.
    std::cerr << "dwtool: unexpected error of unknown type\n";
  }
  return kRuntimeExitCode;
}
