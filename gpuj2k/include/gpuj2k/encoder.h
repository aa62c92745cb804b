#pragma once
// gpuj2k: JPEG 2000 Part 1 (and Part 15, HTJ2K) encoding, the library's public interface with
// gpuj2k/decoder.h and the gpuj2k/common.h both include; nothing else under the project's folders
// is public.
//
//   #include <gpuj2k/encoder.h>
//
//   gpuj2k::ImageView image;  // 8-bit RGB, rows one after another
//   image.data = pixels.data();
//   image.size_bytes = pixels.size();
//   image.width = 640; image.height = 480; image.components = 3;
//   gpuj2k::EncodeOptions options;
//   options.rates_bpp = {0.75};
//   std::vector<std::uint8_t> j2k = gpuj2k::encode(image, options);
//
// Every failure throws gpuj2k::Error (gpuj2k/common.h), whose message is one line that names the
// parameter or file and the problem. Encodes are independent: several may run at once on different
// threads (each with its own worker threads and, where the GPU is used, its own GL context).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gpuj2k/common.h"

namespace gpuj2k {

// An image in the caller's memory. Nothing is copied until the encode reads it, and nothing beyond
// `size_bytes` is ever read: a buffer too small for the layout is an Error.
struct ImageView {
  const void* data = nullptr;
  std::size_t size_bytes = 0;  // length of the buffer at `data`
  int width = 0, height = 0;
  int components = 1;  // 1..16384
  SampleType type = SampleType::UInt8;
  int bits = 0;            // significant bits per sample, at most 16; 0: 8 for UInt8, 16 otherwise
  bool is_signed = false;  // Int32 only (UInt8/UInt16 are unsigned, Int16 is signed)
  Layout layout = Layout::Interleaved;
  std::size_t row_stride = 0;    // bytes from one row to the next (of one plane when planar); 0: tight
  std::size_t plane_stride = 0;  // planar: bytes from one plane to the next; 0: height * row stride
};

// A raw .j2k/.j2c codestream, a .jp2 file, or a .jph file (the JPH file format of T.814 Annex D,
// for HT codestreams: EncodeOptions::ht must be set).
enum class Format { Codestream, Jp2, Jph };
enum class Progression { LRCP, RLCP, RPCL, PCRL, CPRL };

// Code-block mode switches (T.800 Table A.19).
struct CodeBlockModes {
  bool bypass = false;  // raw coding of the lower bit-planes' first two passes
  bool reset = false;   // contexts reset after each pass
  bool terminate_each_pass = false;
  bool vertically_causal = false;
  bool predictable_termination = false;
  bool segmentation_symbols = false;
};

struct EncodeOptions {
  Format format = Format::Codestream;
  // Reversible 5/3 wavelet and colour transform, every bit kept. Otherwise the irreversible 9/7.
  bool lossless = false;
  // Lossy targets, at most one kind; one value per quality layer, increasing quality. None: one
  // layer of everything the quantisation keeps.
  std::vector<double> rates_bpp;                    // bits per pixel over all components
  std::vector<double> ratios;                       // compression ratios of the raw size (as opj_compress -r)
  std::vector<double> psnr_db;                      // PSNR over all components
  double size_bytes = 0;                            // one layer, the whole file at most this size
  double base_step = 1.0 / 2048;                    // lossy quantisation step, relative to the sample range
  int levels = 5;                                   // decomposition levels, 0..32
  std::int64_t tile_width = 0, tile_height = 0;     // 0: one tile
  std::int64_t tile_x0 = 0, tile_y0 = 0;            // tile grid origin on the reference grid
  std::int64_t image_x0 = 0, image_y0 = 0;          // image origin on the reference grid
  int codeblock_width = 64, codeblock_height = 64;  // powers of two 4..1024, product <= 4096
  std::vector<std::pair<int, int>> precincts;       // finest resolution first; empty: maximal
  Progression progression = Progression::LRCP;
  bool sop = false, eph = false;
  CodeBlockModes modes;
  int guard_bits = -1;  // -1: 2 lossless, 1 lossy
  std::string comment = "Created by gpuj2k";
  // JP2/JPH: a resolution box with the capture and/or display resolution, where given (j2kenc
  // passes on the input file's resolution as the capture resolution).
  GridResolution capture_resolution, display_resolution;
  int threads = 0;  // worker threads for this encode; 0: one per hardware thread
  // Shared worker threads and GL context (common.h); `threads` is then the engine's. Null: this
  // encode makes its own.
  std::shared_ptr<Engine> engine;
  DwtDevice dwt = DwtDevice::Auto;
  bool code_every_pass = false;  // with a target: no pass skipping (the same file, slower)
  // HTJ2K (Part 15): every code-block through the high-throughput block coder (one cleanup pass,
  // from the bit-plane rate control picks when there is a target; one quality layer only; no EBCOT
  // mode switches).
  bool ht = false;
  // HT with a target: refinement passes (SigProp, MagRef) after each cleanup, which rate control
  // may keep. false: cleanup passes only, for decoders without HT refinement support (Grok 10).
  bool ht_refinement = true;
  // HT with a byte target, one tile: base_step moved by up to half an octave to where the target
  // puts it (README, "The step's phase"). false: base_step exactly as given.
  bool ht_step_from_target = true;
  // Called from worker threads as code-blocks finish (must be thread-safe): blocks done and the
  // total. Returning false cancels the encode, which then throws Error("encode cancelled").
  std::function<bool(std::size_t done, std::size_t total)> progress;
};

// What an encode reports besides its bytes.
struct EncodeReport {
  int width = 0, height = 0, components = 0;
  int threads = 0;
  std::string dwt_backend;  // where the DWT ran, with the GL renderer for the GPU
  std::string dwt_reason;   // why there
  std::vector<std::string> notices;
  // Milliseconds per stage.
  double read_ms = 0, setup_ms = 0, gl_context_ms = 0, shader_compile_ms = 0, level_shift_ms = 0, upload_ms = 0,
         dwt_ms = 0, download_ms = 0, tier1_ms = 0, rate_control_ms = 0, tier2_ms = 0, release_ms = 0;
  std::size_t recoded_blocks = 0;  // pass skipping: blocks coded again after the allocation
};

// Encodes an image from memory.
GPUJ2K_API std::vector<std::uint8_t> encode(const ImageView& image, const EncodeOptions& options,
                                            EncodeReport* report = nullptr);

// Encodes an image file: PNM (read without conversion), PFM is refused (float samples), anything
// else through OpenImageIO (PNG, TIFF, BMP, JPEG, ...), keeping its precision. A JP2/JPH file gets
// the input file's resolution, where it records one, as its capture resolution (unless
// `options.capture_resolution` is given).
GPUJ2K_API std::vector<std::uint8_t> encode_file(const std::string& input_path, const EncodeOptions& options,
                                                 EncodeReport* report = nullptr);

// The same, written to `output_path` atomically (no file at all on failure).
GPUJ2K_API void encode_file(const std::string& input_path, const std::string& output_path, const EncodeOptions& options,
                            EncodeReport* report = nullptr);

}  // namespace gpuj2k
