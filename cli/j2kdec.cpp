// j2kdec: JPEG 2000 decoder (Part 1 and HTJ2K). Reads a codestream (.j2k, .j2c, .jpc), a JP2 or a
// JPH file and writes PGX (one file per component, NAME_0.pgx, NAME_1.pgx, ... as opj_decompress
// does), our PNM/PFM, or anything OpenImageIO writes. Errors are one line "j2kdec: FILE: problem"
// on stderr, exit 1, and no output file.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <vector>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "codec/decoder/decoder.h"
#include "imageio/atomic_write.h"
#include "imageio/error.h"
#include "imageio/pnm.h"
#include "imageio/write.h"
#include "base/one_line.h"
#include "file_names.h"
#include "timing.h"
#include "quiet_stderr.h"

namespace {

// PGX as the conformance suite and opj_decompress use it: "PG ML +|- depth width height\n", then
// big-endian samples of 1, 2 or 4 bytes. Depths of 33 to 38 bits (T.800 allows 38) take 8 bytes
// each in the same layout, an extension: the suite's files and OpenJPEG's reader stop at 32.
// `samples` after `out`'s header, each as Bytes big-endian bytes.
template <int Bytes, class Sample>
void put_big_endian(const std::vector<Sample>& samples, std::vector<std::uint8_t>& out) {
  std::size_t at = out.size();
  out.resize(at + samples.size() * Bytes);
  for (const Sample v : samples) {
    const auto u = static_cast<std::uint64_t>(v);
    for (int b = Bytes - 1; b >= 0; --b) out[at++] = static_cast<std::uint8_t>(u >> (8 * b));
  }
}

std::vector<std::uint8_t> pgx_bytes(const codec::DecodedComponent& c) {
  const std::string header = "PG ML " + std::string(c.is_signed ? "-" : "+") + " " + std::to_string(c.precision) + " " +
                             std::to_string(c.width) + " " + std::to_string(c.height) + "\n";
  std::vector<std::uint8_t> out(header.begin(), header.end());
  if (c.precision > 31)
    c.precision <= 32 ? put_big_endian<4>(c.wide_samples, out) : put_big_endian<8>(c.wide_samples, out);
  else if (c.precision <= 8)
    put_big_endian<1>(c.samples, out);
  else
    c.precision <= 16 ? put_big_endian<2>(c.samples, out) : put_big_endian<4>(c.samples, out);
  return out;
}

void write_pgx(const std::string& path, const codec::DecodedImage& img) {
  const std::string stem = path.substr(0, path.size() - 4);
  for (std::size_t c = 0; c < img.components.size(); ++c)
    imageio::write_bytes_atomically(stem + "_" + std::to_string(c) + ".pgx", pgx_bytes(img.components[c]));
}

// Writes `img` through OpenImageIO with its ICC profile and resolution, if any (the display
// resolution where the file gives one, else the capture resolution, per pixel of the components'
// grid). A writer may refuse a JP2 file's profile (libpng checks its header): the image is then
// written without it, and the returned line says so. Empty when all went as asked.
std::string write_other(const std::string& path, const codec::DecodedImage& img) {
  const auto& c0 = img.components.at(0);
  int channels = static_cast<int>(img.components.size());
  for (int c = 1; c < channels; ++c) {
    const auto& ci = img.components[static_cast<std::size_t>(c)];
    if (ci.width != c0.width || ci.height != c0.height)
      throw std::runtime_error("components of different sizes (subsampled) can only be written as PGX");
    if (ci.precision != c0.precision || ci.is_signed != c0.is_signed)
      throw std::runtime_error("components of different precisions can only be written as PGX");
  }
  if (c0.precision > 16) throw std::runtime_error("samples of more than 16 bits can only be written as PGX");
  imageio::Image out;
  out.width = c0.width;
  out.height = c0.height;
  out.channels = channels;
  out.bits_per_sample = c0.precision;
  out.is_signed = c0.is_signed;
  out.icc_profile = img.icc_profile;
  const codec::GridResolution& r = img.display_resolution.given() ? img.display_resolution : img.capture_resolution;
  if (r.given()) {
    out.x_pixels_per_metre = r.horizontal / c0.dx;
    out.y_pixels_per_metre = r.vertical / c0.dy;
  }
  out.pixels.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) *
                    static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    const auto& s = img.components[static_cast<std::size_t>(c)].samples;
    for (std::size_t i = 0; i < s.size(); ++i)
      out.pixels[i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)] = static_cast<float>(s[i]);
  }
  try {
    imageio::write_image(path, out);
  } catch (const imageio::IoError& e) {
    if (out.icc_profile.empty()) throw;
    out.icc_profile.clear();
    imageio::write_image(path, out);
    return "its ICC colour profile was refused by the writer and is not in " + path + " (" + e.what() + ")";
  }
  return {};
}

bool is_pnm_path(const std::string& path) {
  const std::string ext = cli::lower_extension(path);
  return ext == ".pgm" || ext == ".ppm" || ext == ".pnm";
}

// Whether a PNM raster holds the decoded image as its integer samples: 1 or 3 unsigned components
// of one size and precision, at most 16 bits.
bool pnm_raster_fits(const codec::DecodedImage& geometry) {
  const auto& comps = geometry.components;
  if (comps.size() != 1 && comps.size() != 3) return false;
  for (const auto& c : comps)
    if (c.width != comps[0].width || c.height != comps[0].height || c.precision != comps[0].precision || c.is_signed ||
        c.precision > 16)
      return false;
  return true;
}

// A PNM output's rows, straight from the decoder into the file's raster (no integer plane per
// component in between: 4 bytes a sample less to allocate, clear and read back). An image the
// raster cannot hold is kept as integer planes, for write_other to say why PNM cannot store it.
class PnmSink : public codec::SampleSink {
 public:
  explicit PnmSink(std::string path) : path_(std::move(path)) {}

  // Deeper samples than PNM holds are refused here, before anything is decoded.
  bool takes_wide_samples() const override { return true; }
  void begin(const codec::DecodedImage& geometry) override {
    for (const auto& c : geometry.components)
      if (c.precision > 16) throw std::runtime_error("samples of more than 16 bits can only be written as PGX");
    image_ = geometry;
    if (pnm_raster_fits(geometry)) {
      const auto& c0 = geometry.components[0];
      raster_.emplace(path_, c0.width, c0.height, static_cast<int>(geometry.components.size()), c0.precision);
      return;
    }
    for (auto& c : image_.components)
      c.samples.assign(static_cast<std::size_t>(c.width) * static_cast<std::size_t>(c.height), 0);
  }
  void put_row(std::size_t component, std::size_t x, std::size_t y, std::span<const std::int32_t> samples) override {
    if (raster_) return raster_->put_row(static_cast<int>(component), x, y, samples);
    auto& c = image_.components[component];
    std::copy(samples.begin(), samples.end(), c.samples.begin() + static_cast<std::ptrdiff_t>(y * c.width + x));
  }
  void put_rows012(std::size_t x, std::size_t y, std::span<const std::int32_t> c0, std::span<const std::int32_t> c1,
                   std::span<const std::int32_t> c2) override {
    if (raster_ && image_.components.size() == 3) return raster_->put_rgb_row(x, y, c0, c1, c2);
    SampleSink::put_rows012(x, y, c0, c1, c2);
  }

  void write() {
    if (raster_)
      raster_->write();
    else
      write_other(path_, image_);  // PNM: no profile (j2kdec says so before writing)
  }

 private:
  std::string path_;
  codec::DecodedImage image_;  // the geometry; the samples too when there is no raster
  std::optional<imageio::PnmRaster> raster_;
};

// "0,2,1" -> {0, 2, 1}; "X,Y,W,H" -> the region [X, X+W) x [Y, Y+H). One line on failure.
std::vector<long long> numbers(const std::string& list, const char* what) {
  std::vector<long long> out;
  std::size_t pos = 0;
  while (pos <= list.size()) {
    const std::size_t comma = std::min(list.find(',', pos), list.size());
    const std::string field = list.substr(pos, comma - pos);
    std::size_t used = 0;
    long long v = -1;
    try {
      v = std::stoll(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (field.empty() || used != field.size() || v < 0 || v > (1LL << 32))
      throw std::runtime_error(std::string(what) + " \"" + list + "\": \"" + field + "\" is not a number in 0..2^32");
    out.push_back(v);
    pos = comma + 1;
  }
  return out;
}

codec::DecodeRegion region_of(const std::string& text) {
  const auto v = numbers(text, "--region");
  if (v.size() != 4) throw std::runtime_error("--region \"" + text + "\" must be X,Y,W,H");
  if (v[2] == 0 || v[3] == 0) throw std::runtime_error("--region \"" + text + "\" is empty");
  return codec::DecodeRegion{v[0], v[1], v[0] + v[2], v[1] + v[3]};
}

// The stage report of --timing: one line per stage, or one JSON object, on stderr.
void print_timing(const std::string& mode, const codec::DecodeReport& r, double output_ms, double measured_ms) {
  const codec::DecodeStageTimes& t = r.times;
  const cli::TimedStage stages[] = {{"input read", t.read},
                                    {"header parse", t.parse},
                                    {"setup", t.setup},
                                    {"GL context creation", t.gl_context},
                                    {"shader compilation", t.shader_compile},
                                    {"tier-2", t.tier2},
                                    {"tier-1 + dequantization", t.tier1},
                                    {"upload", t.upload},
                                    {"inverse DWT compute", t.dwt},
                                    {"download", t.download},
                                    {"inverse MCT + DC shift", t.component_transform},
                                    {"output", output_ms}};
  cli::print_timing(mode, {"j2kdec", r.dwt_backend, r.dwt_reason, r.threads, stages, measured_ms, {}});
}

codec::DwtDevice device_of(const std::string& name) {
  if (name == "gpu") return codec::DwtDevice::Gpu;
  if (name == "auto") return codec::DwtDevice::Auto;
  return codec::DwtDevice::Cpu;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"j2kdec: JPEG 2000 decoder, Part 1 and HTJ2K (Part 15): codestreams, JP2 and JPH files"};
  std::string input, output, dwt = "cpu", components, region;
  int reduce = 0, layers = 0, threads = 0;
  double max_memory_mib = 2048;
  bool quiet = false;
  app.add_option("-i,--input", input, "codestream (.j2k, .j2c, .jpc), JP2 or JPH file")->required();
  app.add_option("-o,--output", output,
                 "output image: .pgx (one file per component), .pgm/.ppm/.pnm, .pfm, or any OpenImageIO format")
      ->required();
  app.add_option("--reduce", reduce, "discard the R finest resolution levels")->check(CLI::Range(0, 32));
  app.add_option("--layers", layers, "decode only the first L quality layers (0: all)")->check(CLI::NonNegativeNumber);
  app.add_option("--components", components, "decode only these components, written in this order (e.g. 0,2)");
  app.add_option(
      "--region", region,
      "decode only the window X,Y,W,H of the reference grid (full-resolution coordinates, image offset included, "
      "as opj_decompress -d X,Y,X+W,Y+H)");
  app.add_option("--dwt", dwt,
                 "where the inverse 9/7 DWT runs: cpu (default), gpu (any GL context, software ones included) or auto "
                 "(a hardware GPU where it is faster for the image size, never a software renderer, as j2kenc); the "
                 "5/3 runs on the CPU")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}));
  app.add_option("--threads", threads, "CPU threads (0: one per hardware thread)")->check(CLI::NonNegativeNumber);
  app.add_option("--max-memory", max_memory_mib, "refuse streams that need more than this many MiB")
      ->check(CLI::PositiveNumber);
  app.add_flag("-q,--quiet", quiet, "no warnings");
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "a summary line: size, components, time, where the DWT ran and why");
  std::string timing;
  app.add_flag("--timing{text}", timing,
               "print the time of each stage after the decode; --timing=json for JSON on stderr");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  const std::string ext = cli::lower_extension(output);
  if (!timing.empty() && timing != "text" && timing != "json") {
    std::fprintf(stderr, "j2kdec: --timing takes text or json, got \"%s\"\n", base::one_line(timing).c_str());
    return 2;
  }
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
  const auto t0 = Clock::now();
  try {
    codec::DecodeOptions options;
    options.reduce = reduce;
    options.max_layers = layers;
    options.threads = threads;
    options.max_memory = static_cast<std::size_t>(max_memory_mib * 1048576.0);
    if (!components.empty())
      for (const long long c : numbers(components, "--components"))
        options.components.push_back(static_cast<int>(std::min(c, 1LL << 30)));
    if (!region.empty()) options.region = region_of(region);
    options.dwt = device_of(dwt);
    codec::DecodeReport report;
    // PNM output takes the rows as they are made; the other writers take the decoded image.
    std::optional<PnmSink> pnm;
    if (is_pnm_path(output)) pnm.emplace(output);
    const codec::DecodedImage image =
        pnm ? codec::decode_file_to(input, *pnm, options, &report) : codec::decode_file(input, options, &report);
    if (!quiet)
      for (const std::string& w : image.warnings)
        std::fprintf(stderr, "j2kdec: %s: warning: %s\n", input.c_str(), base::one_line(w).c_str());
    if (!quiet && !image.icc_profile.empty() && (pnm || ext == ".pgx"))
      std::fprintf(stderr,
                   "j2kdec: %s: warning: its ICC colour profile (%zu bytes) is not written: %s files cannot carry "
                   "one (TIFF and PNG can)\n",
                   input.c_str(), image.icc_profile.size(), pnm ? "PNM" : "PGX");
    const auto write_start = Clock::now();
    std::string write_note;  // what the writer left out, said once stderr is ours again
    try {
      // libpng inside OpenImageIO prints its own lines; j2kdec says what went wrong itself.
      const cli::QuietStderr quiet_libraries;
      if (pnm)
        pnm->write();
      else if (ext == ".pgx")
        write_pgx(output, image);
      else
        write_note = write_other(output, image);
    } catch (const imageio::IoError& e) {
      std::fprintf(stderr, "j2kdec: %s\n", base::one_line(e.what()).c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "j2kdec: %s: %s\n", output.c_str(), base::one_line(e.what()).c_str());
      return 1;
    }
    if (!write_note.empty() && !quiet)
      std::fprintf(stderr, "j2kdec: %s: warning: %s\n", input.c_str(), base::one_line(write_note).c_str());
    const double output_ms = since(write_start);
    const double ms = since(t0);
    if (!timing.empty()) print_timing(timing, report, output_ms, ms);
    if (verbose)
      std::fprintf(stderr, "j2kdec: %s -> %s: %lldx%lld, %zu components, %.1f ms, DWT on %s (%s)\n", input.c_str(),
                   output.c_str(), static_cast<long long>(image.x1 - image.x0),
                   static_cast<long long>(image.y1 - image.y0), image.components.size(), ms, report.dwt_backend.c_str(),
                   report.dwt_reason.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "j2kdec: %s: %s\n", input.c_str(), base::one_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
