#include "transform.h"

#include "quiet_stderr.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "backends.h"
#include "dwt/error.h"
#include "dwt/kernel.h"
#include "dwt/plane.h"
#include "imageio/pfm.h"
#include "imageio/read.h"
#include "imageio/write.h"
#include "planes.h"
#include "summary.h"

namespace dwtool {

namespace {

bool has_pfm_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return extension == ".pfm";
}

// Coefficients are float32 planes in the Mallat layout; PFM is the one format that holds them.
void check_file_kinds(const Request& request) {
  if (request.direction == Direction::Forward && !has_pfm_extension(request.output)) {
    throw std::runtime_error(request.output + ": forward output must be a .pfm file");
  }
  if (request.direction == Direction::Inverse && !has_pfm_extension(request.input)) {
    throw std::runtime_error(request.input + ": inverse input must be a .pfm coefficient file");
  }
}

// dwt::validate knows what is wrong but not which file the plane came from.
void validate_plane(const Request& request, const imageio::Image& image) {
  try {
    dwt::validate(request.params, image.width, image.height);
  } catch (const dwt::DwtError& e) {
    throw std::runtime_error(request.input + ": " + e.what());
  }
}

// Times only the backend call: reading, converting and writing are not the engine's cost.
template <class T>
double transform_plane(dwt::DwtBackend& backend, const Request& request, std::vector<T>& samples, int width,
                       int height) {
  const auto span = dwt::make_span(samples.data(), width, height);
  const auto start = std::chrono::steady_clock::now();
  if (request.direction == Direction::Forward) {
    backend.forward(span, request.params);
  } else {
    backend.inverse(span, request.params);
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Forward output and .pfm inverse output are float32 as they are; anything else is an integer image.
void write_output(const Request& request, std::vector<float> samples, int width, int height) {
  if (has_pfm_extension(request.output)) {
    imageio::write_pfm(request.output, float_image(std::move(samples), width, height));
    return;
  }
  const IntegerImage result = quantise(samples, width, height, request.bits);
  imageio::write_image(request.output, result.image);
  if (result.clamped > 0 && !request.quiet) {
    std::cerr << "dwtool: note: " << result.clamped << " samples clamped to [0, " << ((1 << request.bits) - 1)
              << "] in " << request.output << '\n';
  }
}

}  // namespace

void run(const Request& request) {
  check_file_kinds(request);
  const std::unique_ptr<dwt::DwtBackend> backend = make_backend(request);
  const imageio::Image image = [&] {
    const cli::QuietStderr quiet_libraries;  // one line of ours, none of libpng's
    return imageio::read_greyscale(request.input);
  }();
  validate_plane(request, image);
  const int width = image.width;
  const int height = image.height;

  // Before the clock starts, so the GPU's context creation is not charged to the transform.
  const std::string renderer = prepare(*backend);
  if (!renderer.empty() && !request.quiet) std::cerr << "dwtool: renderer: " << renderer << '\n';

  const bool forward = request.direction == Direction::Forward;
  double milliseconds = 0;
  std::vector<float> result;
  if (dwt::get_kernel(request.params.kernel).reversible) {
    std::vector<std::int32_t> plane = integer_samples(image, request.input, forward ? "sample" : "coefficient");
    milliseconds = transform_plane(*backend, request, plane, width, height);
    if (has_pfm_extension(request.output)) {
      result = exact_floats(plane, width, request.output);
    } else {
      // Bound for quantise(), which clamps far below 2^24, so float rounding cannot matter.
      result.assign(plane.begin(), plane.end());
    }
  } else {
    result = float_samples(image, request.input);
    milliseconds = transform_plane(*backend, request, result, width, height);
  }
  write_output(request, std::move(result), width, height);

  if (!request.quiet) {
    std::cerr << summary_line(request.direction, request.params, width, height, backend->name(), milliseconds)
              << stage_times(*backend) << '\n';
  }
}

}  // namespace dwtool
