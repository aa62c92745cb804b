#include "command_line.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "dwt/kernel.h"
#include "base/one_line.h"

namespace dwtool {

namespace {

constexpr int kUsageExitCode = 2;

// Both subcommands take the same options and bind them to the same RawOptions; only the one that
// was given writes to it. --bits concerns integer output images, which only inverse produces.
void add_transform_options(CLI::App& command, RawOptions& raw, bool inverse) {
  command
      .add_option("-i,--input", raw.input,
                  inverse ? "Coefficient plane (.pfm, one channel)"
                          : "Greyscale image (PNG, PGM, TIFF, ... or PFM); samples keep their integer values")
      ->required();
  command
      .add_option("-o,--output", raw.output,
                  inverse ? "Reconstructed image: .pfm for float samples, else an integer image (see --bits)"
                          : "Coefficients in the Mallat layout (.pfm)")
      ->required();
  command.add_option("--kernel", raw.kernel, "Wavelet: " + std::string(dwt::kernel_names()))->capture_default_str();
  command.add_option("--levels", raw.levels, "Decomposition levels")->capture_default_str();
  command.add_option("--boundary", raw.boundary, "Boundary extension: sym|per|zero")->capture_default_str();
  command.add_option("--backend", raw.backend, "cpu|gpu")->capture_default_str();
  command.add_option("--origin", raw.origin, "Reference-grid position X,Y of the top-left sample")
      ->capture_default_str();
  command.add_option("--threads", raw.threads, "CPU threads, 0 = all hardware threads")->capture_default_str();
  if (inverse) {
    command.add_option("--bits", raw.bits, "8|16: sample size of an integer output image")->capture_default_str();
  }
  command.add_option("--gl", raw.gl,
                     "GL platform for --backend gpu: auto|egl-device|egl-surfaceless|osmesa "
                     "(default: $GPUJ2K_GL, else auto)");
  command.add_flag("-q,--quiet", raw.quiet, "Print nothing but errors");
}

}  // namespace

ParsedCommandLine parse_command_line(int argc, char** argv) {
  CLI::App app{"Runs one 2-D discrete wavelet transform of the gpuj2k engine on an image file.", "dwtool"};
  app.require_subcommand(1);
  RawOptions raw;
  CLI::App* forward = app.add_subcommand("forward", "Image -> wavelet coefficients (PFM, Mallat layout)");
  CLI::App* inverse = app.add_subcommand("inverse", "Wavelet coefficients (PFM) -> image");
  add_transform_options(*forward, raw, false);
  add_transform_options(*inverse, raw, true);
  AppOptions app_options;
  const std::vector<CLI::App*> app_commands = add_app_commands(app, app_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return {std::nullopt, std::nullopt, app.exit(e)};  // --help
  } catch (const CLI::ParseError& e) {
    // CLI11's own report spans two lines; dwtool's contract is one.
    std::cerr << "dwtool: " << base::one_line(e.what()) << " (see --help)\n";
    return {std::nullopt, std::nullopt, kUsageExitCode};
  }
  for (std::size_t i = 0; i < app_commands.size(); ++i) {
    if (app.got_subcommand(app_commands[i])) {
      app_options.command = static_cast<AppCommand>(i);
      ParsedCommandLine parsed;
      parsed.app = app_options;
      return parsed;
    }
  }
  raw.direction = app.got_subcommand(inverse) ? Direction::Inverse : Direction::Forward;
  return {raw, std::nullopt, 0};
}

}  // namespace dwtool
