// j2kenc: JPEG 2000 encoder. Reads any image OpenImageIO reads (and our PNM/PFM), writes a raw
// codestream (.j2k, .j2c, .jpc), a JP2 file (.jp2) or, with --ht, a JPH file (.jph). Errors are
// one line on stderr, a non-zero exit, and no output file.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <mutex>

#include <unistd.h>
#include <cmath>
#include <optional>
#include <cstdio>
#include <string>

#include "gpuj2k/encoder.h"
#include "imageio/atomic_write.h"
#include "file_names.h"
#include "number_pairs.h"
#include "base/one_line.h"
#include "quiet_stderr.h"
#include "timing.h"

namespace {

constexpr std::int64_t kMaxCoordinate = (std::int64_t{1} << 32) - 1;

gpuj2k::Progression parse_order(const std::string& name) {
  const char* names[] = {"LRCP", "RLCP", "RPCL", "PCRL", "CPRL"};
  const gpuj2k::Progression orders[] = {gpuj2k::Progression::LRCP, gpuj2k::Progression::RLCP, gpuj2k::Progression::RPCL,
                                        gpuj2k::Progression::PCRL, gpuj2k::Progression::CPRL};
  for (int i = 0; i < 5; ++i)
    if (name == names[i]) return orders[i];
  throw std::invalid_argument("unknown progression order '" + name + "' (expected LRCP, RLCP, RPCL, PCRL or CPRL)");
}

// Code-block mode switches (T.800 Table A.19), named as in common encoders' documentation.
gpuj2k::CodeBlockModes parse_modes(const std::string& list) {
  gpuj2k::CodeBlockModes s;
  std::size_t start = 0;
  while (start <= list.size() && !list.empty()) {
    const std::size_t comma = list.find(',', start);
    const std::string m = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (m == "bypass")
      s.bypass = true;
    else if (m == "reset")
      s.reset = true;
    else if (m == "termall" || m == "restart")
      s.terminate_each_pass = true;
    else if (m == "vcausal" || m == "causal")
      s.vertically_causal = true;
    else if (m == "pterm" || m == "erterm")
      s.predictable_termination = true;
    else if (m == "segsym" || m == "segmark")
      s.segmentation_symbols = true;
    else
      throw std::invalid_argument("unknown code-block mode '" + m +
                                  "' (expected bypass, reset, termall, vcausal, pterm, segsym)");
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return s;
}

std::vector<double> parse_numbers(const std::string& list, const std::string& option) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || item.empty() || !(v > 0))
      throw std::invalid_argument(option + " takes positive numbers separated by commas, got \"" + list + "\"");
    out.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// "X,Y" pixels per metre (horizontal, then vertical) as a resolution box holds them.
gpuj2k::GridResolution parse_resolution(const std::string& pair, const std::string& option) {
  const std::vector<double> v = parse_numbers(pair, option);
  if (v.size() != 2) throw std::invalid_argument(option + " takes X,Y in pixels per metre, got \"" + pair + "\"");
  return gpuj2k::GridResolution{v[1], v[0]};
}

// JasPer-style "-O key=value" options, mapped onto ours (JasPer's rate is a fraction of the
// uncompressed size; numrlvls counts resolutions, one more than decomposition levels).
struct JasperOptions {
  std::vector<double> rates;  // ilyrrates..., rate
  std::optional<int> levels, tile_width, tile_height, cblk_width, cblk_height;
  std::optional<bool> lossless;
  std::optional<std::string> order;
};

JasperOptions parse_jasper(const std::vector<std::string>& items) {
  JasperOptions j;
  std::vector<double> intermediate;
  std::optional<double> rate;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("-O takes key=value, got \"" + item + "\"");
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    auto integer = [&] {
      const auto v = parse_numbers(value, "-O " + key);
      if (v.size() != 1 || v[0] != std::floor(v[0])) throw std::invalid_argument("-O " + key + " takes one integer");
      return static_cast<int>(v[0]);
    };
    if (key == "rate")
      rate = parse_numbers(value, "-O rate").at(0);
    else if (key == "ilyrrates")
      intermediate = parse_numbers(value, "-O ilyrrates");
    else if (key == "numrlvls")
      j.levels = integer() - 1;
    else if (key == "mode") {
      if (value != "int" && value != "real") throw std::invalid_argument("-O mode takes int or real");
      j.lossless = value == "int";
    } else if (key == "tilewidth")
      j.tile_width = integer();
    else if (key == "tileheight")
      j.tile_height = integer();
    else if (key == "cblkwidth")
      j.cblk_width = integer();
    else if (key == "cblkheight")
      j.cblk_height = integer();
    else if (key == "prg") {
      std::string upper = value;
      for (auto& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      j.order = upper;
    } else
      throw std::invalid_argument(
          "unknown -O option '" + key +
          "' (rate, numrlvls, mode, tilewidth, tileheight, cblkwidth, cblkheight, prg, ilyrrates)");
  }
  if (!intermediate.empty() && !rate) throw std::invalid_argument("-O ilyrrates needs -O rate for the last layer");
  j.rates = intermediate;
  if (rate) j.rates.push_back(*rate);
  return j;
}

// A progress bar on stderr for encodes that take more than about a second, only when stderr is a
// terminal: tier-1 over the code-blocks is the long stage, and the encoder reports each one.
class ProgressBar {
 public:
  // Writes to file descriptor `fd` (stderr's own, while libraries' output is silenced).
  ProgressBar(bool enabled, int fd) : enabled_(enabled), fd_(fd), start_(std::chrono::steady_clock::now()) {}
  ~ProgressBar() {
    if (shown_) ::dprintf(fd_, "\r%60s\r", "");  // leave the line clean for the summary
  }
  void update(std::size_t done, std::size_t total) {
    if (!enabled_ || total == 0) return;
    const std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    shown_ = true;
    const int filled = static_cast<int>(30.0 * static_cast<double>(done) / static_cast<double>(total));
    ::dprintf(fd_, "\rj2kenc: [%-30s] %3d%% code-blocks", std::string(static_cast<std::size_t>(filled), '#').c_str(),
              static_cast<int>(100.0 * static_cast<double>(done) / static_cast<double>(total)));
  }

 private:
  bool enabled_;
  int fd_;
  bool shown_ = false;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_{};
};

// The stage report of --timing: one line per stage, or one JSON object, on stderr.
void print_timing(const std::string& mode, const gpuj2k::EncodeReport& r, double output_ms, double measured_ms) {
  const cli::TimedStage stages[] = {{"input read", r.read_ms},
                                    {"setup", r.setup_ms},
                                    {"GL context creation", r.gl_context_ms},
                                    {"shader compilation", r.shader_compile_ms},
                                    {"level shift + MCT", r.level_shift_ms},
                                    {"upload", r.upload_ms},
                                    {"DWT compute", r.dwt_ms},
                                    {"download", r.download_ms},
                                    {"quantization + tier-1", r.tier1_ms},
                                    {"rate control", r.rate_control_ms},
                                    {"tier-2", r.tier2_ms},
                                    {"release", r.release_ms},
                                    {"output", output_ms}};
  cli::TimingReport report{"j2kenc", r.dwt_backend, r.dwt_reason, r.threads, stages, measured_ms, {}};
  report.counts.emplace_back("recoded_blocks", r.recoded_blocks);
  cli::print_timing(mode, report);
  if (mode != "json" && r.recoded_blocks > 0)
    std::fprintf(stderr, "  (pass skipping: %zu blocks stopped or skipped too soon were coded again)\n",
                 r.recoded_blocks);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "j2kenc: JPEG 2000 encoder. Lossy 9/7 (on the GPU when one is there) unless --lossless.\n\n"
      "Examples:\n"
      "  j2kenc -i photo.png -o photo.jp2 --rate 0.75          # 0.75 bits per pixel over all components\n"
      "  j2kenc -i photo.png -o photo.j2k --ratio 40,20,10     # three quality layers, OpenJPEG-style ratios\n"
      "  j2kenc -i photo.png -o photo.j2k --psnr 32,38 --dwt gpu\n"
      "  j2kenc -i photo.png -o photo.jp2 -O rate=0.05 -O numrlvls=6   # JasPer-style options\n"
      "  j2kenc -i scan.pgm -o scan.j2k --lossless --tile 512x512 --order RPCL --precincts 128x128,64x64\n"};
  std::string input, output, tile, tile_origin, origin, codeblock = "64x64", precincts, order = "LRCP", modes, comment;
  std::string rate, ratio, psnr, dwt = "auto";
  std::vector<std::string> jasper;
  double size = 0, base_step = 1.0 / 2048;
  bool lossless = false, sop = false, eph = false, quiet = false;
  int levels = 5, threads = 0, guard_bits = -1;
  app.add_option("-i,--input", input, "input image (PNG, PNM, TIFF, BMP, JPEG, ...)")->required();
  app.add_option("-o,--output", output, "output: .j2k/.j2c/.jpc codestream, .jp2 file, or .jph file (HTJ2K, with --ht)")
      ->required();
  app.add_flag("--lossless", lossless, "reversible 5/3 wavelet and RCT, every bit kept");
  app.add_option("--levels", levels, "decomposition levels (default 5)");
  app.add_option("--tile", tile, "tile size WxH (default: one tile)");
  app.add_option("--tile-origin", tile_origin, "tile grid origin X,Y on the reference grid (XTOsiz,YTOsiz)");
  app.add_option("--origin", origin, "image origin X,Y on the reference grid (XOsiz,YOsiz)");
  app.add_option("--codeblock", codeblock, "code-block size WxH, powers of two 4..1024, W*H <= 4096 (default 64x64)");
  app.add_option("--precincts", precincts,
                 "precinct sizes WxH,... finest resolution first; the last is halved for coarser ones");
  app.add_option("--order", order, "progression order: LRCP, RLCP, RPCL, PCRL, CPRL (default LRCP)");
  bool ht = false;
  app.add_flag("--ht", ht, "HTJ2K: code every code-block with the high-throughput block coder of Part 15 (T.814)");
  bool ht_cleanup_only = false;
  app.add_flag("--ht-cleanup-only", ht_cleanup_only,
               "with --ht and a target: no SigProp/MagRef refinement passes (for decoders without them, as Grok 10)");
  app.add_flag("--sop", sop, "SOP marker before every packet");
  app.add_flag("--eph", eph, "EPH marker after every packet header");
  app.add_option("--modes", modes, "code-block mode switches: bypass,reset,termall,vcausal,pterm,segsym");
  app.add_option("--rate", rate, "lossy: bits per pixel over all components, one per quality layer (BPP[,BPP...])");
  app.add_option("--ratio", ratio,
                 "lossy: compression ratios as opj_compress -r, one per layer (R[,R...], decreasing)");
  app.add_option("--psnr", psnr, "lossy: PSNR targets in dB, one per layer (DB[,DB...])");
  app.add_option("--size", size, "lossy: whole-file size in bytes");
  app.add_option("--dwt", dwt,
                 "where the 9/7 DWT runs: cpu, gpu or auto (default auto: a hardware GPU where it is faster for the "
                 "image size, never a software renderer)");
  CLI::Option* base_step_given =
      app.add_option("--base-step", base_step,
                     "lossy: quantisation step relative to the sample range (default 1/2048; with --ht and a byte "
                     "target, moved by up to half an octave to suit the target unless given)");
  app.add_option("-O", jasper,
                 "JasPer-style option key=value: rate, numrlvls, mode=int|real, tilewidth, tileheight, cblkwidth, "
                 "cblkheight, prg, ilyrrates");
  app.add_option("--guard-bits", guard_bits, "guard bits (default 2 lossless, 1 lossy)");
  app.add_option("--comment", comment, "COM marker text (default: the encoder's name)");
  std::string capture_resolution, display_resolution;
  app.add_option("--capture-resolution", capture_resolution,
                 "JP2/JPH: capture resolution in pixels per metre, X,Y (as grk_compress -Q; default: the input "
                 "file's, where it records one)");
  app.add_option("--display-resolution", display_resolution,
                 "JP2/JPH: display resolution in pixels per metre, X,Y (as grk_compress -D)");
  app.add_option("--threads", threads, "worker threads (default: all hardware threads)");
  bool every_pass = false;
  app.add_flag("--code-every-pass", every_pass,
               "with a byte or PSNR target, code every pass of every block instead of stopping far below the predicted "
               "threshold");
  app.add_flag("-q,--quiet", quiet, "no summary line");
  std::string timing;
  app.add_flag("--timing{text}", timing,
               "print the time of each stage after the encode; --timing=json for JSON on stderr");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "j2kenc: %s\n", base::one_line(e.what()).c_str());
    return 2;
  }

  try {
    const std::string ext = cli::lower_extension(output);
    gpuj2k::Format format;
    if (ext == ".jp2")
      format = gpuj2k::Format::Jp2;
    else if (ext == ".jph")
      format = gpuj2k::Format::Jph;
    else if (ext == ".j2k" || ext == ".j2c" || ext == ".jpc")
      format = gpuj2k::Format::Codestream;
    else
      throw std::invalid_argument(output + ": unknown output type (use .jp2, .jph, .j2k, .j2c or .jpc)");
    const JasperOptions jo = parse_jasper(jasper);
    if (jo.lossless) lossless = lossless || *jo.lossless;
    if (jo.levels) levels = *jo.levels;
    if (jo.order) order = *jo.order;
    const int targets_given = !rate.empty() + !ratio.empty() + !psnr.empty() + (size > 0) + !jo.rates.empty();
    if (targets_given > 1) throw std::invalid_argument("give one of --rate, --ratio, --psnr, --size and -O rate");
    if (lossless && targets_given)
      throw std::invalid_argument("rate and quality targets need lossy coding (drop --lossless)");

    gpuj2k::EncodeOptions options;
    options.format = format;
    options.lossless = lossless;
    options.base_step = base_step;
    options.ht_step_from_target = base_step_given->count() == 0;
    if (dwt == "cpu")
      options.dwt = gpuj2k::DwtDevice::Cpu;
    else if (dwt == "gpu")
      options.dwt = gpuj2k::DwtDevice::Gpu;
    else if (dwt == "auto")
      options.dwt = gpuj2k::DwtDevice::Auto;
    else
      throw std::invalid_argument("--dwt takes cpu, gpu or auto, got \"" + dwt + "\"");
    options.levels = levels;
    options.threads = threads;
    options.code_every_pass = every_pass;
    options.ht = ht;
    if (ht_cleanup_only && !ht) throw std::invalid_argument("--ht-cleanup-only needs --ht");
    options.ht_refinement = !ht_cleanup_only;
    options.guard_bits = guard_bits;
    options.sop = sop;
    options.eph = eph;
    options.progression = parse_order(order);
    if (!modes.empty()) options.modes = parse_modes(modes);
    if (!comment.empty()) options.comment = comment;
    if (!capture_resolution.empty())
      options.capture_resolution = parse_resolution(capture_resolution, "--capture-resolution");
    if (!display_resolution.empty())
      options.display_resolution = parse_resolution(display_resolution, "--display-resolution");
    if (!tile.empty())
      std::tie(options.tile_width, options.tile_height) = cli::parse_pair(tile, 'x', "--tile", kMaxCoordinate);
    if (!tile_origin.empty())
      std::tie(options.tile_x0, options.tile_y0) = cli::parse_pair(tile_origin, ',', "--tile-origin", kMaxCoordinate);
    if (!origin.empty())
      std::tie(options.image_x0, options.image_y0) = cli::parse_pair(origin, ',', "--origin", kMaxCoordinate);
    const auto cb = cli::parse_pair(codeblock, 'x', "--codeblock", 1 << 20);
    options.codeblock_width = static_cast<int>(cb.first);
    options.codeblock_height = static_cast<int>(cb.second);
    if (!precincts.empty())
      for (const auto& [w, h] : cli::parse_size_list(precincts, "--precincts", 1 << 20))
        options.precincts.emplace_back(static_cast<int>(w), static_cast<int>(h));
    if (options.tile_width == 0 && !tile.empty()) throw std::invalid_argument("--tile sizes must be positive");
    if (jo.tile_width) options.tile_width = *jo.tile_width;
    if (jo.tile_height) options.tile_height = *jo.tile_height;
    if (jo.cblk_width) options.codeblock_width = *jo.cblk_width;
    if (jo.cblk_height) options.codeblock_height = *jo.cblk_height;
    if (!rate.empty()) options.rates_bpp = parse_numbers(rate, "--rate");
    if (!ratio.empty()) options.ratios = parse_numbers(ratio, "--ratio");
    for (double r : jo.rates) options.ratios.push_back(1.0 / r);  // JasPer's rate: a fraction of the raw size
    if (size > 0) options.size_bytes = size;
    if (!psnr.empty()) options.psnr_db = parse_numbers(psnr, "--psnr");
    if (!timing.empty() && timing != "text" && timing != "json")
      throw std::invalid_argument("--timing takes text or json, got \"" + timing + "\"");

    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point t) {
      return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
    };
    const auto t0 = Clock::now();
    gpuj2k::EncodeReport report;
    std::vector<std::uint8_t> bytes;
    {
      // Third-party libraries (libpng inside OpenImageIO, Mesa) keep their own lines off stderr;
      // the progress bar writes to the real one.
      const bool show_progress = !quiet && ::isatty(2);
      const cli::QuietStderr quiet_libraries;
      ProgressBar bar(show_progress, quiet_libraries.real_stderr());
      if (show_progress)
        options.progress = [&bar](std::size_t done, std::size_t total) {
          bar.update(done, total);
          return true;
        };
      bytes = gpuj2k::encode_file(input, options, &report);
    }
    if (!quiet)
      for (const auto& notice : report.notices) std::fprintf(stderr, "j2kenc: note: %s\n", notice.c_str());
    const auto write_start = Clock::now();
    imageio::write_bytes_atomically(output, bytes);
    const double output_ms = since(write_start);
    const double ms = since(t0);
    if (!timing.empty()) print_timing(timing, report, output_ms, ms);
    if (!quiet)
      std::fprintf(stderr, "j2kenc: %s -> %s: %dx%d, %d components, %zu bytes (%.4f bpp), %.1f ms, DWT on %s (%s)\n",
                   input.c_str(), output.c_str(), report.width, report.height, report.components, bytes.size(),
                   8.0 * static_cast<double>(bytes.size()) / (static_cast<double>(report.width) * report.height), ms,
                   report.dwt_backend.c_str(), report.dwt_reason.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "j2kenc: %s\n", base::one_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
