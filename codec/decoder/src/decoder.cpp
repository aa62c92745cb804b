#include "codec/decoder/decoder.h"

#include <fstream>
#include <iterator>
#include <memory>
#include <optional>

#include "codestream_reader.h"
#include "dwt_cpu/cpu_backend.h"
#include "jp2_colour.h"
#include "jp2_reader.h"
#include "tile_decoder.h"

namespace codec {

namespace {

std::int64_t reduced(std::int64_t v, int r) { return ceil_shift(v, r); }

// The output image: each component's area on its grid (B-12), reduced, sized before any tile is
// decoded, and refused if it alone exceeds the memory limit.
DecodedImage allocate_image(const dec::Siz& siz, const DecodeOptions& options) {
  DecodedImage img;
  const int r = options.reduce;
  img.x0 = reduced(siz.grid.image.x0, r);
  img.y0 = reduced(siz.grid.image.y0, r);
  img.x1 = reduced(siz.grid.image.x1, r);
  img.y1 = reduced(siz.grid.image.y1, r);
  double bytes = 0;
  for (const dec::ComponentSize& c : siz.components) {
    const Rect area = tile_component_rect(siz.grid.image, c.dx, c.dy);
    const std::int64_t w = reduced(area.x1, r) - reduced(area.x0, r), h = reduced(area.y1, r) - reduced(area.y0, r);
    bytes += static_cast<double>(w) * static_cast<double>(h) * sizeof(std::int32_t);
  }
  if (bytes > static_cast<double>(options.max_memory))
    throw DecodeError("the image would need " + std::to_string(static_cast<long long>(bytes / 1048576)) +
                      " MiB, over the memory limit of " + std::to_string(options.max_memory >> 20) + " MiB");
  for (const dec::ComponentSize& c : siz.components) {
    if (c.precision > 31)
      throw DecodeError("components of " + std::to_string(c.precision) + " bits are not supported yet (at most 31)");
    const Rect area = tile_component_rect(siz.grid.image, c.dx, c.dy);
    DecodedComponent out;
    out.x0 = static_cast<int>(reduced(area.x0, r));
    out.y0 = static_cast<int>(reduced(area.y0, r));
    out.width = static_cast<int>(reduced(area.x1, r) - out.x0);
    out.height = static_cast<int>(reduced(area.y1, r) - out.y0);
    out.dx = c.dx;
    out.dy = c.dy;
    out.precision = c.precision;
    out.is_signed = c.is_signed;
    out.samples.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), 0);
    img.components.push_back(std::move(out));
  }
  return img;
}

}  // namespace

DecodedImage decode(std::span<const std::uint8_t> bytes, const DecodeOptions& options) {
  if (options.reduce < 0 || options.reduce > 32) throw DecodeError("reduce must be in 0..32");
  if (options.max_layers < 0) throw DecodeError("the layer count must not be negative");
  std::span<const std::uint8_t> stream = bytes;
  std::size_t base = 0;
  std::optional<dec::Jp2File> jp2;
  if (dec::looks_like_jp2(bytes)) {
    jp2 = dec::read_jp2(bytes);
    stream = jp2->codestream;
    base = jp2->codestream_offset;
  }
  const dec::Codestream cs = dec::read_codestream(stream, base);
  DecodedImage image = allocate_image(cs.siz, options);
  image.warnings = cs.warnings;

  double image_bytes = 0;
  for (const DecodedComponent& c : image.components) image_bytes += static_cast<double>(c.samples.size()) * 4;
  dwt_cpu::CpuBackend cpu(options.threads);
  dec::TileDecodeSetup setup;
  setup.options = &options;
  setup.reversible_backend = &cpu;
  setup.irreversible_backend = options.irreversible_backend ? options.irreversible_backend : &cpu;
  setup.memory_budget = static_cast<std::size_t>(static_cast<double>(options.max_memory) - image_bytes);

  std::vector<bool> seen(static_cast<std::size_t>(cs.siz.grid.tile_count()), false);
  for (const dec::TileStream& tile : cs.tiles) {
    dec::decode_tile(cs, tile, setup, image);
    seen[static_cast<std::size_t>(tile.index)] = true;
  }
  int missing = 0;
  for (bool s : seen) missing += s ? 0 : 1;
  if (missing > 0)
    image.warnings.push_back(std::to_string(missing) + " of " + std::to_string(seen.size()) +
                             " tile(s) missing from the stream; their samples are 0");
  if (jp2) dec::apply_jp2_channels(*jp2, options.jp2_sycc_to_srgb, image);
  return image;
}

DecodedImage decode_file(const std::string& path, const DecodeOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DecodeError("cannot open the file");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw DecodeError("cannot read the file");
  return decode(bytes, options);
}

}  // namespace codec
