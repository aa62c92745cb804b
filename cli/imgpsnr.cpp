// imgpsnr: PSNR between a reference image and a test image (say, a decoded JPEG 2000 file), per
// channel and over all channels. The peak is 2^bits - 1 with bits taken from the reference image
// unless --bits is given (float images: peak 1 unless --bits). Identical images give "inf".
// Errors (unreadable files, images of different shapes) are one line on stderr and exit status 1.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "imageio/read.h"
#include "base/one_line.h"
#include "psnr.h"
#include "quiet_stderr.h"

namespace {

std::string number(double v, const char* format) {
  if (std::isinf(v)) return "inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string json_number(double v, const char* format) { return std::isinf(v) ? "\"inf\"" : number(v, format); }

std::string json_list(const std::vector<double>& values, const char* format) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + json_number(values[i], format);
  return out + "]";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "imgpsnr: PSNR of TEST against REFERENCE, per channel and over all channels.\n"
      "Peak 2^bits - 1, bits from the reference image unless --bits is given (float images: peak 1).\n"
      "Identical images print inf. With --json, one JSON object on stdout (inf as the string \"inf\")."};
  std::string reference_path, test_path;
  int bits = 0;
  bool json = false;
  app.add_option("REFERENCE", reference_path, "the original image")->required();
  app.add_option("TEST", test_path, "the image to compare with it (e.g. a decoded codestream)")->required();
  app.add_option("--bits", bits, "sample precision for the peak value 2^bits - 1 (1..32)")->check(CLI::Range(1, 32));
  app.add_flag("--json", json, "print one JSON object instead of text");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "imgpsnr: %s\n", base::one_line(e.what()).c_str());
    return 2;
  }

  try {
    imageio::Image reference, test;
    {
      const cli::QuietStderr quiet_libraries;
      reference = imageio::read_image(reference_path);
      test = imageio::read_image(test_path);
    }
    int used_bits = bits;
    if (used_bits == 0 && !reference.is_float) used_bits = reference.bits_per_sample;
    const double peak = used_bits > 0 ? cli::peak_for_bits(used_bits) : 1.0;
    const cli::PsnrResult r = cli::psnr_with_peak(reference, test, peak);

    if (json) {
      std::printf(
          "{\"width\": %d, \"height\": %d, \"channels\": %d, \"bits\": %d, \"peak\": %s, "
          "\"channel_db\": %s, \"channel_mse\": %s, \"all_db\": %s, \"all_mse\": %s}\n",
          reference.width, reference.height, reference.channels, used_bits, number(peak, "%.17g").c_str(),
          json_list(r.channel_db, "%.6f").c_str(), json_list(r.channel_mse, "%.9g").c_str(),
          json_number(r.all_db, "%.6f").c_str(), json_number(r.all_mse, "%.9g").c_str());
      return 0;
    }
    const std::string peak_text =
        used_bits > 0 ? number(peak, "%.17g") + " (" + std::to_string(used_bits) + " bits)" : "1 (float samples)";
    std::printf("%dx%d, %d %s, peak %s\n", reference.width, reference.height, reference.channels,
                reference.channels == 1 ? "channel" : "channels", peak_text.c_str());
    for (std::size_t c = 0; c < r.channel_db.size(); ++c)
      std::printf("channel %zu: PSNR %s dB, MSE %s\n", c, number(r.channel_db[c], "%.4f").c_str(),
                  number(r.channel_mse[c], "%.6g").c_str());
    std::printf("all: PSNR %s dB, MSE %s\n", number(r.all_db, "%.4f").c_str(), number(r.all_mse, "%.6g").c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "imgpsnr: %s\n", base::one_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
