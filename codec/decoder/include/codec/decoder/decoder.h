#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

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
  // The inverse DWT of irreversible (9/7) tile-components; null: the CPU lifting backend. The
  // reversible 5/3 always runs on the CPU (exact integers).
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
  int precision = 8;   // 1..38 (the samples here are int32: decoding refuses more than 31 bits)
  bool is_signed = false;
  std::vector<std::int32_t> samples;  // row-major, width * height
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
};

// Decodes a JPEG 2000 codestream (SOC first) or a JP2 file (signature box first). Throws
// DecodeError.
DecodedImage decode(std::span<const std::uint8_t> bytes, const DecodeOptions& options = {});
DecodedImage decode_file(const std::string& path, const DecodeOptions& options = {});

// What decode would give, from the headers alone: the image area and each output component's
// geometry (no samples) after reduce, region and selection. A JP2 file's palette, channel
// definitions and colour conversion are not applied (its components are the codestream's).
DecodedImage read_header(std::span<const std::uint8_t> bytes, const DecodeOptions& options = {});

}  // namespace codec
