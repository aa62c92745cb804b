// j2kenc: JPEG 2000 encoder. Reads any image OpenImageIO reads (and our PNM/PFM), writes a raw
// codestream (.j2k, .j2c, .jpc) or a JP2 file (.jp2). Errors are one line on stderr, a non-zero
// exit, and no output file.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <string>

#include "codec/encoder/encoder.h"
#include "codec/structure/error.h"
#include "imageio/atomic_write.h"
#include "imageio/read.h"
#include "number_pairs.h"
#include "one_line.h"
#include "quiet_stderr.h"

namespace {

constexpr std::int64_t kMaxCoordinate = (std::int64_t{1} << 32) - 1;

std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  std::string ext = path.substr(dot);
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

codec::Progression parse_order(const std::string& name) {
  const char* names[] = {"LRCP", "RLCP", "RPCL", "PCRL", "CPRL"};
  for (int i = 0; i < 5; ++i)
    if (name == names[i]) return static_cast<codec::Progression>(i);
  throw std::invalid_argument("unknown progression order '" + name + "' (expected LRCP, RLCP, RPCL, PCRL or CPRL)");
}

// Code-block mode switches (T.800 Table A.19), named as in common encoders' documentation.
codec::t1::BlockStyle parse_modes(const std::string& list) {
  codec::t1::BlockStyle s;
  std::size_t start = 0;
  while (start <= list.size() && !list.empty()) {
    const std::size_t comma = list.find(',', start);
    const std::string m = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (m == "bypass") s.bypass = true;
    else if (m == "reset") s.reset = true;
    else if (m == "termall" || m == "restart") s.terminate_each_pass = true;
    else if (m == "vcausal" || m == "causal") s.vertically_causal = true;
    else if (m == "pterm" || m == "erterm") s.predictable_termination = true;
    else if (m == "segsym" || m == "segmark") s.segmentation_symbols = true;
    else throw std::invalid_argument("unknown code-block mode '" + m + "' (expected bypass, reset, termall, vcausal, pterm, segsym)");
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"j2kenc: JPEG 2000 encoder (reversible 5/3 lossless path)\n\n"
               "Examples:\n"
               "  j2kenc -i photo.png -o photo.jp2 --lossless\n"
               "  j2kenc -i scan.pgm -o scan.j2k --lossless --tile 512x512 --order RPCL --precincts 128x128,64x64\n"};
  std::string input, output, tile, tile_origin, origin, codeblock = "64x64", precincts, order = "LRCP", modes, comment;
  bool lossless = false, sop = false, eph = false, quiet = false;
  int levels = 5, threads = 0, guard_bits = 2;
  app.add_option("-i,--input", input, "input image (PNG, PNM, TIFF, BMP, JPEG, ...)")->required();
  app.add_option("-o,--output", output, "output: .j2k/.j2c/.jpc codestream or .jp2 file")->required();
  app.add_flag("--lossless", lossless, "reversible 5/3 wavelet and RCT, every bit kept");
  app.add_option("--levels", levels, "decomposition levels (default 5)");
  app.add_option("--tile", tile, "tile size WxH (default: one tile)");
  app.add_option("--tile-origin", tile_origin, "tile grid origin X,Y on the reference grid (XTOsiz,YTOsiz)");
  app.add_option("--origin", origin, "image origin X,Y on the reference grid (XOsiz,YOsiz)");
  app.add_option("--codeblock", codeblock, "code-block size WxH, powers of two 4..1024, W*H <= 4096 (default 64x64)");
  app.add_option("--precincts", precincts, "precinct sizes WxH,... finest resolution first; the last is halved for coarser ones");
  app.add_option("--order", order, "progression order: LRCP, RLCP, RPCL, PCRL, CPRL (default LRCP)");
  app.add_flag("--sop", sop, "SOP marker before every packet");
  app.add_flag("--eph", eph, "EPH marker after every packet header");
  app.add_option("--modes", modes, "code-block mode switches: bypass,reset,termall,vcausal,pterm,segsym");
  app.add_option("--guard-bits", guard_bits, "guard bits (default 2)");
  app.add_option("--comment", comment, "COM marker text (default: the encoder's name)");
  app.add_option("--threads", threads, "worker threads (default: all hardware threads)");
  app.add_flag("-q,--quiet", quiet, "no summary line");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "j2kenc: %s\n", cli::one_line(e.what()).c_str());
    return 2;
  }

  try {
    const std::string ext = lower_extension(output);
    codec::FileFormat format;
    if (ext == ".jp2") format = codec::FileFormat::Jp2;
    else if (ext == ".j2k" || ext == ".j2c" || ext == ".jpc") format = codec::FileFormat::Codestream;
    else throw std::invalid_argument(output + ": unknown output type (use .jp2, .j2k, .j2c or .jpc)");
    if (!lossless) throw std::invalid_argument("lossy coding is not available yet; pass --lossless");

    codec::EncodeParams params;
    params.lossless = lossless;
    params.levels = levels;
    params.threads = threads;
    params.guard_bits = guard_bits;
    params.sop = sop;
    params.eph = eph;
    params.order = parse_order(order);
    if (!modes.empty()) params.block_style = parse_modes(modes);
    if (!comment.empty()) params.comment = comment;
    if (!tile.empty()) std::tie(params.tile_width, params.tile_height) = cli::parse_pair(tile, 'x', "--tile", kMaxCoordinate);
    if (!tile_origin.empty()) std::tie(params.tile_x0, params.tile_y0) = cli::parse_pair(tile_origin, ',', "--tile-origin", kMaxCoordinate);
    if (!origin.empty()) std::tie(params.image_x0, params.image_y0) = cli::parse_pair(origin, ',', "--origin", kMaxCoordinate);
    const auto cb = cli::parse_pair(codeblock, 'x', "--codeblock", 1 << 20);
    params.codeblock_width = static_cast<int>(cb.first);
    params.codeblock_height = static_cast<int>(cb.second);
    if (!precincts.empty())
      for (const auto& [w, h] : cli::parse_size_list(precincts, "--precincts", 1 << 20))
        params.precincts.emplace_back(static_cast<int>(w), static_cast<int>(h));
    if (params.tile_width == 0 && !tile.empty()) throw std::invalid_argument("--tile sizes must be positive");
    codec::validate(params);  // before reading: option errors should not wait for a large image

    const auto t0 = std::chrono::steady_clock::now();
    const codec::SourceImage image = [&] {
      const cli::QuietStderr quiet_libraries;
      return codec::to_source_image(imageio::read_image(input), input);
    }();
    const std::vector<std::uint8_t> bytes = codec::encode(image, params, format);
    imageio::write_bytes_atomically(output, bytes);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!quiet)
      std::fprintf(stderr, "j2kenc: %s -> %s: %dx%d, %zu components, %zu bytes, %.1f ms\n", input.c_str(), output.c_str(),
                   image.width, image.height, image.components.size(), bytes.size(), ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "j2kenc: %s\n", cli::one_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
