#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "codec/dwt_choice/dwt_device.h"
#include "codec/structure/grid_resolution.h"

namespace dwt {
class DwtBackend;
}

namespace codec {

// Every decoder failure a malformed or unsupported stream causes: one line, no trailing newline,
// naming the byte offset where the problem lies when there is one. Never a crash or a hang: every
// length, count and size of the stream is checked before it is used or allocated.
class DecodeError : public std::runtime_error {
 public:
  explicit DecodeError(const std::string& what) : std::runtime_error(what) {}
};

// A window of the image on the reference grid (T.800 B.2), half-open: [x0, x1) x [y0, y1), in the
// full-resolution coordinates SIZ uses (image offset included, as opj_decompress -d takes them).
struct DecodeRegion {
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct DecodeOptions {
  int reduce = 0;      // discard this many of the finest resolution levels (opj_decompress -r)
  int max_layers = 0;  // decode only the first max_layers quality layers; 0 = all
  // Refuse streams whose image, tile structure or working buffers would need more than this.
  std::size_t max_memory = std::size_t{2} << 30;
  // Where the inverse DWT of irreversible (9/7) tile-components runs, chosen as the encoder chooses
  // (codec/dwt_choice): Cpu, Gpu (any GL context, or a DecodeError) or Auto (a hardware GPU where
  // its calibrated costs beat the CPU for the planes to transform, never a software rasteriser).
  // The reversible 5/3 always runs on the CPU (exact integers).
  DwtDevice dwt = DwtDevice::Cpu;
  // The caller's own backend for the 9/7 instead of `dwt`'s choice; null: `dwt` decides.
  dwt::DwtBackend* irreversible_backend = nullptr;
  int threads = 0;  // threads of tier-1 and the CPU DWT; 0 = one per hardware thread
  // JP2 files: turn sYCC (colr EnumCS 18) into sRGB, as a viewer shows it. The palette (pclr /
  // cmap) and channel definitions (cdef) are always applied: they say what the channels are.
  bool jp2_sycc_to_srgb = true;
  // Decode only these codestream components, output in this order; empty: all. Components the
  // component transform needs (0..2 when COD's MCT is on) are decoded but not output. A JP2
  // file's palette, channel definitions and colour conversion are not applied to a selection.
  std::vector<int> components;
  // Decode only this window (clipped to the image): tiles outside it are skipped, and code-blocks
  // whose reach through the inverse DWT misses it are not decoded. Each component then covers
  // the window on its own (reduced) grid, as B-12 maps the image area.
  std::optional<DecodeRegion> region;
};

// One decoded component on its own sampling grid: the component's samples inside the image area,
// i.e. [ceil(XOsiz/XRsiz), ceil(Xsiz/XRsiz)) x [ceil(YOsiz/YRsiz), ceil(Ysiz/YRsiz)) (T.800 B-12),
// reduced by 2^reduce. Samples are the stream's integers: unsigned 0..2^precision-1 or signed.
struct DecodedComponent {
  int width = 0, height = 0;
  int x0 = 0, y0 = 0;  // top-left on the component's (reduced) grid
  int dx = 1, dy = 1;  // XRsiz, YRsiz
  int precision = 8;   // 1..38
  bool is_signed = false;
  std::vector<std::int32_t> samples;  // row-major, width * height; empty when precision > 31
  // Components of more than 31 bits (T.800 allows 38): their samples, as `samples` holds the others.
  std::vector<std::int64_t> wide_samples;
};

struct DecodedImage {
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // image area on the reference grid (reduced)
  std::vector<DecodedComponent> components;
  // Problems that did not stop the decode (a truncated stream, an unknown marker): one line each.
  std::vector<std::string> warnings;
  // JP2 files: the colour space of `components` (16 sRGB, 17 greyscale, 18 sYCC; 16 after an
  // sYCC conversion), 0 for a codestream or a JP2 file without an enumerated colr box. For a JP2
  // file, `components` are its channels: palette applied, colours in the colour space's order.
  int jp2_colour_space = 0;
  // JP2 files with a restricted ICC colr box (METH 2): the profile, for the output file to carry;
  // the samples are not converted. Empty otherwise.
  std::vector<std::uint8_t> icc_profile;
  // JP2 files with a resolution box: the capture (resc) and default display (resd) resolutions, on
  // the decoded image's grid (the file's divided by 2^reduce).
  GridResolution capture_resolution, display_resolution;
};

// Milliseconds spent in each stage of one decode, in data-flow order (the encoder's StageTimes,
// reversed). Threaded stages are the wall time of the stage, not the workers' summed time. GPU
// stages are measured with the device idle before each clock read, so they are real, not estimates.
struct DecodeStageTimes {
  double read = 0;            // decode_file: the file into memory
  double parse = 0;           // JP2 boxes, main and tile-part headers
  double setup = 0;           // the output image, worker threads, the DWT choice (less the GL times below)
  double gl_context = 0;      // creating the GL context, and releasing it at the end (GPU DWT only)
  double shader_compile = 0;  // compiling the DWT shader (GPU DWT only)
  double tier2 = 0;           // each tile's structure and its packets: headers and code-block data
  // Code-block decoding (EBCOT or HT) with each block's ROI de-scaling and dequantisation into the
  // DWT's plane, one stage as the encoder's "quantization + tier-1": timing them apart would take a
  // second pass over the plane.
  double tier1 = 0;
  double upload = 0;               // planes to the GPU
  double dwt = 0;                  // the inverse transform itself
  double download = 0;             // planes back from the GPU
  double component_transform = 0;  // inverse MCT, DC level shift and clamping, JP2 palette and colour
  double total() const {
    return read + parse + setup + gl_context + shader_compile + tier2 + tier1 + upload + dwt + download +
           component_transform;
  }
};

// What a decode tells its caller besides the image.
struct DecodeReport {
  DecodeStageTimes times;
  int threads = 0;
  std::string dwt_backend;  // the backend of the 9/7, with its renderer for the GPU
  std::string dwt_reason;   // why that backend (--dwt auto's decision, or what was asked)
};

// Decodes a JPEG 2000 codestream (SOC first) or a JP2 file (signature box first). Throws
// DecodeError.
DecodedImage decode(std::span<const std::uint8_t> bytes, const DecodeOptions& options = {},
                    DecodeReport* report = nullptr);
DecodedImage decode_file(const std::string& path, const DecodeOptions& options = {}, DecodeReport* report = nullptr);

// Where decode_to hands the decoded samples, a row at a time, for the caller to store in its own
// format: an 8-bit raster, a file's buffer, a caller's image. The decoder then keeps no image of
// its own (four bytes per sample that would be allocated, cleared, filled and copied once more).
// Rows are the final samples, as DecodedComponent::samples would hold them; coordinates are
// relative to the output component's top-left (0 <= x, x + size <= width, 0 <= y < height).
// Called from the decoder's worker threads, several at once, each sample exactly once (those of
// tiles missing from the stream as zeros, as decode gives them). A sink may throw: the decode then
// stops and rethrows it. After any error, what the sink got is a part of the image.
class SampleSink {
 public:
  virtual ~SampleSink() = default;
  // Called once before any row: the output's geometry (components, sizes, precisions, colour
  // space), every `samples` empty. The place to size the sink's storage or refuse the image.
  virtual void begin(const DecodedImage& /*geometry*/) {}
  // Samples [x, x + samples.size()) of row y of output component `component`.
  virtual void put_row(std::size_t component, std::size_t x, std::size_t y, std::span<const std::int32_t> samples) = 0;
  // The same for a component of more than 31 bits, to a sink that takes them (decode_to refuses
  // such an image, before decoding, for a sink that does not).
  virtual bool takes_wide_samples() const { return false; }
  virtual void put_row_wide(std::size_t component, std::size_t x, std::size_t y, std::span<const std::int64_t> samples);
  // The same span of row y of output components 0, 1 and 2 at once (equal sizes), as the inverse
  // component transform makes them, for a sink that interleaves them; by default three put_row.
  virtual void put_rows012(std::size_t x, std::size_t y, std::span<const std::int32_t> c0,
                           std::span<const std::int32_t> c1, std::span<const std::int32_t> c2) {
    put_row(0, x, y, c0);
    put_row(1, x, y, c1);
    put_row(2, x, y, c2);
  }
};

// Decodes as decode does, handing every sample to `sink` instead of keeping it: the image
// returned has its components' geometry (and warnings, colour space) with empty `samples`. Where
// the output needs the whole image first (a component selection, a JP2 palette, channel
// definitions or sYCC conversion), the image is decoded as decode does and then handed over.
DecodedImage decode_to(std::span<const std::uint8_t> bytes, SampleSink& sink, const DecodeOptions& options = {},
                       DecodeReport* report = nullptr);
DecodedImage decode_file_to(const std::string& path, SampleSink& sink, const DecodeOptions& options = {},
                            DecodeReport* report = nullptr);

// What decode would give, from the headers alone: the image area and each output component's
// geometry (no samples) after reduce, region and selection. A JP2 file's palette, channel
// definitions and colour conversion are not applied (its components are the codestream's).
DecodedImage read_header(std::span<const std::uint8_t> bytes, const DecodeOptions& options = {});

}  // namespace codec
