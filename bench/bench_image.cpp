// bench_image: the input images of bench/table41 and bench/psnr.
//
//   bench_image mosaic --size N --kodak DIR -o OUT
//       A square 8-bit RGB image: a crop of one Kodak photograph or, for sizes no single photograph
//       covers, a mosaic of kodim01..16 tiled left to right, top to bottom (the layout dwt_bench uses
//       for its luma planes). Prints one line saying what the image holds.
//   bench_image convert IN -o OUT
//       Rewrites IN with the very samples our reader gives (e.g. a PNG as a PPM).
//
// Why the scripts hand PNM copies to every encoder: opj_compress 2.5 applies a PNG's gAMA chunk while
// reading (OpenJPEG issue #1330), and the Kodak PNGs carry gAMA 1/2.2, so it would encode a darker
// image than the others and score about 12 dB. A PNM has no such chunk, so all four encoders see the
// same samples. The output format follows OUT's extension (.ppm/.pgm: our own PNM writer).
//
// Errors are one line on stderr and exit status 1 (2 for bad arguments).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_images.h"
#include "imageio/read.h"
#include "imageio/write.h"

namespace {
namespace fs = std::filesystem;

constexpr const char* kUsage = "usage: bench_image mosaic --size N --kodak DIR -o OUT | bench_image convert IN -o OUT";

int usage_error(const std::string& message) {
  std::fprintf(stderr, "bench_image: %s (%s)\n", message.c_str(), kUsage);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage_error("no command");
  const std::string command = argv[1];
  if (command != "mosaic" && command != "convert") return usage_error("unknown command \"" + command + "\"");
  int size = 0;
  std::string kodak, output, input;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--size" || arg == "--kodak" || arg == "-o") && i + 1 < argc) {
      const std::string value = argv[++i];
      if (arg == "--size") {
        char* end = nullptr;
        const long v = std::strtol(value.c_str(), &end, 10);
        if (value.empty() || *end != '\0' || v < 1 || v > 65535)
          return usage_error("--size takes 1..65535, got \"" + value + "\"");
        size = static_cast<int>(v);
      } else if (arg == "--kodak") {
        kodak = value;
      } else {
        output = value;
      }
    } else if (command == "convert" && input.empty() && !arg.starts_with("-")) {
      input = arg;
    } else {
      return usage_error("unexpected argument \"" + arg + "\"");
    }
  }
  if (output.empty()) return usage_error("-o OUT is required");
  if (command == "mosaic" && (size == 0 || kodak.empty())) return usage_error("mosaic needs --size and --kodak");
  if (command == "convert" && input.empty()) return usage_error("convert needs an input image");
  try {
    if (command == "convert") {
      imageio::write_image(output, imageio::read_image(input));
      return 0;
    }
    int used = 0;
    imageio::write_image(output, bench::kodak_mosaic(size, kodak, used));
    if (used == 1)
      std::printf("crop of a Kodak photograph (RGB)\n");
    else
      std::printf("mosaic of %d Kodak photograph tiles (RGB)\n", used);
  } catch (const std::exception& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    std::fprintf(stderr, "bench_image: %s\n", what.c_str());
    return 1;
  }
  return 0;
}
