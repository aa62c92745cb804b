#pragma once
// gpuj2k: JPEG 2000 decoding, beside the encoder: Part 1 and HTJ2K (Part 15) codestreams, JP2 and
// JPH files.
//
//   #include <gpuj2k/decoder.h>
//
//   gpuj2k::DecodedImage image = gpuj2k::decode(bytes.data(), bytes.size());  // library-allocated
//   const gpuj2k::DecodedComponent& red = image.components[0];                 // int32 samples
//
//   // or into the caller's buffer, 8-bit interleaved RGB of the size read_info gives:
//   gpuj2k::ImageInfo info = gpuj2k::read_info(bytes.data(), bytes.size());
//   std::vector<std::uint8_t> rgb(info.width() * info.height() * 3);
//   gpuj2k::OutputView out{rgb.data(), rgb.size(), info.width(), info.height(), 3};
//   gpuj2k::decode_into(bytes.data(), bytes.size(), out);
//
// A malformed, truncated or hostile stream is a gpuj2k::Error whose message is one line naming the
// problem (and the byte offset where there is one); nothing is read outside the given bytes and no
// size is allocated before it is checked against DecodeOptions::max_memory.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gpuj2k/common.h"

namespace gpuj2k {

// A window of the image in full-resolution reference-grid coordinates (image offset included, as
// opj_decompress -d takes them): [x, x + width) x [y, y + height).
struct Region {
  std::int64_t x = 0, y = 0, width = 0, height = 0;
};

struct DecodeOptions {
  int reduce = 0;                // discard this many of the finest resolution levels
  int layers = 0;                // decode only the first `layers` quality layers; 0: all
  std::vector<int> components;   // codestream components to output, in this order; empty: all
  std::optional<Region> region;  // decode only this window (clipped to the image)
  // Refuse streams whose image, tiles or working buffers would need more than this many bytes.
  std::size_t max_memory = std::size_t{2} << 30;
  int threads = 0;  // CPU threads of the inverse DWT; 0: one per hardware thread
  // Where the inverse 9/7 runs: Gpu, any GL context (fragment shaders); Auto, as the encoder chooses
  // (a hardware GPU where it is faster for the image size, never a software renderer).
  DwtDevice dwt = DwtDevice::Cpu;
  bool sycc_to_srgb = true;  // JP2 files: sYCC (colr 18) converted to sRGB, as a viewer shows it
};

// One decoded component (or JP2 channel) on its own sampling grid.
struct ComponentInfo {
  int width = 0, height = 0;
  int x0 = 0, y0 = 0;  // top-left on the component's (reduced) grid
  int dx = 1, dy = 1;  // subsampling (XRsiz, YRsiz)
  int precision = 8;   // bits, 1..38
  bool is_signed = false;
};

struct ImageInfo {
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the decoded area on the (reduced) reference grid
  std::vector<ComponentInfo> components;
  int colour_space = 0;  // JP2/JPH: 16 sRGB, 17 greyscale, 18 sYCC (16 after conversion); 0: none given
  // JP2/JPH with a restricted ICC colour specification: the profile (samples are not converted).
  std::vector<std::uint8_t> icc_profile;
  // JP2/JPH resolution box: capture (resc) and display (resd), on the decoded image's grid (the
  // file's values divided by 2^reduce).
  GridResolution capture_resolution, display_resolution;
  int width() const { return static_cast<int>(x1 - x0); }
  int height() const { return static_cast<int>(y1 - y0); }
};

struct DecodedComponent : ComponentInfo {
  std::vector<std::int32_t> samples;  // row-major, width * height: unsigned 0..2^precision-1, or signed
  // Components of more than 31 bits (JPEG 2000 allows 38): their samples, `samples` then empty.
  std::vector<std::int64_t> wide_samples;
};

struct DecodedImage {
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  std::vector<DecodedComponent> components;
  int colour_space = 0;
  std::vector<std::uint8_t> icc_profile;                  // as ImageInfo's
  GridResolution capture_resolution, display_resolution;  // as ImageInfo's
  std::vector<std::string> warnings;  // what did not stop the decode (a truncated stream): one line each
  int width() const { return static_cast<int>(x1 - x0); }
  int height() const { return static_cast<int>(y1 - y0); }
};

// The caller's buffer for decode_into: width x height pixels of `components` samples each, of one
// type, interleaved or planar, with any strides. Nothing beyond size_bytes is ever written.
struct OutputView {
  void* data = nullptr;
  std::size_t size_bytes = 0;
  int width = 0, height = 0;
  int components = 1;
  SampleType type = SampleType::UInt8;
  Layout layout = Layout::Interleaved;
  std::size_t row_stride = 0;    // 0: tight
  std::size_t plane_stride = 0;  // planar: 0 is height * row stride
};

// What a decode reports besides the image (the encoder's EncodeReport, for the decoder's stages in
// data-flow order). Threaded stages are wall times, not the workers' summed time.
struct DecodeReport {
  int threads = 0;
  std::string dwt_backend;  // where the inverse 9/7 ran, with the GL renderer for the GPU
  std::string dwt_reason;   // why there
  // Milliseconds per stage.
  double read_ms = 0, parse_ms = 0, setup_ms = 0, gl_context_ms = 0, shader_compile_ms = 0, tier2_ms = 0, tier1_ms = 0,
         upload_ms = 0, dwt_ms = 0, download_ms = 0, component_transform_ms = 0;
};

// What decode would give, from the headers alone (nothing is decoded): the size and components
// after reduce, region and component selection. For a JP2 file whose palette or channel
// definitions make its channels, the channels are those of the codestream's components (decode
// and decode_into report the channels themselves).
GPUJ2K_API ImageInfo read_info(const void* data, std::size_t size, const DecodeOptions& options = {});

// Decodes a codestream (SOC first), or a JP2 or JPH file (signature box first), into int32 planes.
GPUJ2K_API DecodedImage decode(const void* data, std::size_t size, const DecodeOptions& options = {},
                               DecodeReport* report = nullptr);
GPUJ2K_API DecodedImage decode_file(const std::string& path, const DecodeOptions& options = {},
                                    DecodeReport* report = nullptr);

// Decodes into the caller's buffer. Every output component must have the view's width and height
// (no subsampling left after decoding), there must be as many as the view's, and each sample must
// fit the view's type (UInt8: unsigned up to 8 bits; UInt16: unsigned up to 16; Int16: signed up
// to 16 or unsigned up to 15; Int32: up to 31 bits): otherwise an Error says what the image is. Returns the
// warnings.
GPUJ2K_API std::vector<std::string> decode_into(const void* data, std::size_t size, const OutputView& out,
                                                const DecodeOptions& options = {}, DecodeReport* report = nullptr);

}  // namespace gpuj2k
