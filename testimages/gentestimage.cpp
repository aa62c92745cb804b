// gentestimage: writes one of the synthetic test images to a file.
//
//   gentestimage --pattern zoneplate --size 512x512 --channels 3 --bits 12 -o zp.png
//
// Any failure prints one line on stderr and exits with 1; the output file is
// written atomically, so a failed run never leaves a partial file behind.

#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdint>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "imageio/write.h"
#include "testimages/patterns.h"

namespace {

struct Size {
  int width = 0;
  int height = 0;
};

int parse_side(std::string_view text, const std::string& whole) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size()) {
    throw std::invalid_argument("--size must look like WIDTHxHEIGHT, got \"" + whole + "\"");
  }
  return value;
}

// "WIDTHxHEIGHT"; the range is checked by testimages::generate.
Size parse_size(const std::string& text) {
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos) {
    throw std::invalid_argument("--size must look like WIDTHxHEIGHT, got \"" + text + "\"");
  }
  const std::string_view view(text);
  return {parse_side(view.substr(0, x), text), parse_side(view.substr(x + 1), text)};
}

std::uint64_t parse_seed(const std::string& text) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size()) {
    throw std::invalid_argument("--seed must be an integer 0..18446744073709551615, got \"" + text + "\"");
  }
  return value;
}

std::string pattern_list() {
  std::string names;
  for (testimages::Pattern pattern : testimages::kAllPatterns) {
    if (!names.empty()) names += ", ";
    names += testimages::pattern_name(pattern);
  }
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Generate a deterministic synthetic test image.", "gentestimage"};
  std::string pattern_text;
  std::string size_text;
  int channels = 1;
  int bits = 8;
  bool is_signed = false;
  std::string output;
  app.add_option("--pattern", pattern_text, "One of: " + pattern_list())->required();
  app.add_option("--size", size_text, "WIDTHxHEIGHT, each 1..65535")->required();
  app.add_option("--channels", channels, "Number of channels")->capture_default_str();
  app.add_option("--bits", bits, "Bits per sample, 1..16")->capture_default_str();
  app.add_flag("--signed", is_signed, "Signed samples instead of unsigned");
  // Parsed by us: CLI11 silently wraps "-3" or 2^64 into a uint64_t.
  std::string seed_text = "1";
  app.add_option("--seed", seed_text, "Seed for the noise in the noise and mix patterns, 0..2^64-1")
      ->capture_default_str();
  app.add_option("-o,--output", output, "Output file; the extension picks the format (png, pgm, ppm, tif, pfm, ...)")
      ->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help
  } catch (const CLI::ParseError& e) {
    // CLI11's own report spans two lines; the contract is one.
    std::cerr << "gentestimage: " << e.what() << " (see --help)\n";
    return 1;
  }

  try {
    const Size size = parse_size(size_text);
    const std::uint64_t seed = parse_seed(seed_text);
    const testimages::Pattern pattern = testimages::parse_pattern(pattern_text);
    const imageio::Image image =
        testimages::generate(pattern, size.width, size.height, channels, bits, is_signed, seed);
    imageio::write_image(output, image);
  } catch (const std::exception& e) {
    std::cerr << "gentestimage: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
