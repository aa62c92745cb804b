#include "codec/codestream/siz.h"

#include <string>

#include "codec/codestream/error.h"
#include "codec/codestream/marker_segment.h"
#include "codec/codestream/markers.h"

namespace codec::cs {
namespace {

constexpr std::uint64_t kU32Max = 0xFFFFFFFFu;
constexpr std::size_t kMaxComponents = 16384;  // Csiz range, T.800 Table A.9
constexpr std::uint64_t kMaxTiles = 65535;     // Isot is 0..65534 (Table A.5)

void check_u32(const char* name, std::uint64_t v) {
  if (v > kU32Max) throw CodestreamError(std::string("SIZ: ") + name + " = " + std::to_string(v) + " exceeds 2^32-1");
}

std::string num(std::uint64_t v) { return std::to_string(v); }

// The relations of T.800 A.5.1 along one axis: a non-empty image, a tile grid origin at or before
// the image origin, and a first tile that overlaps the image.
void check_axis(char axis, std::uint64_t size, std::uint64_t origin, std::uint64_t tile, std::uint64_t tile_origin) {
  const std::string a(1, axis);
  if (tile == 0) throw CodestreamError("SIZ: " + a + "Tsiz must be at least 1");
  if (!(origin < size))
    throw CodestreamError("SIZ: " + a + "Osiz (" + num(origin) + ") must be less than " + a + "siz (" + num(size) +
                          ")");
  if (!(tile_origin <= origin))
    throw CodestreamError("SIZ: " + a + "TOsiz (" + num(tile_origin) + ") must not exceed " + a + "Osiz (" +
                          num(origin) + ")");
  if (!(tile_origin + tile > origin))
    throw CodestreamError("SIZ: " + a + "TOsiz + " + a + "Tsiz (" + num(tile_origin + tile) + ") must exceed " + a +
                          "Osiz (" + num(origin) + ") so that the first tile overlaps the image");
}

std::uint64_t ceil_div(std::uint64_t a, std::uint64_t b) { return a / b + (a % b != 0 ? 1 : 0); }

}  // namespace

void validate_siz(const Siz& siz) {
  check_u32("Xsiz", siz.xsiz);
  check_u32("Ysiz", siz.ysiz);
  check_u32("XOsiz", siz.xosiz);
  check_u32("YOsiz", siz.yosiz);
  check_u32("XTsiz", siz.xtsiz);
  check_u32("YTsiz", siz.ytsiz);
  check_u32("XTOsiz", siz.xtosiz);
  check_u32("YTOsiz", siz.ytosiz);
  check_axis('X', siz.xsiz, siz.xosiz, siz.xtsiz, siz.xtosiz);
  check_axis('Y', siz.ysiz, siz.yosiz, siz.ytsiz, siz.ytosiz);

  const std::size_t n = siz.components.size();
  if (n < 1 || n > kMaxComponents)
    throw CodestreamError("SIZ: " + std::to_string(n) + " components; Csiz must be 1..16384");
  for (std::size_t i = 0; i < n; ++i) {
    const SizComponent& c = siz.components[i];
    const std::string who = "SIZ: component " + std::to_string(i) + " ";
    if (c.precision < 1 || c.precision > 38)
      throw CodestreamError(who + "precision " + std::to_string(c.precision) + " is outside 1..38");
    if (c.xrsiz < 1 || c.xrsiz > 255)
      throw CodestreamError(who + "XRsiz " + std::to_string(c.xrsiz) + " is outside 1..255");
    if (c.yrsiz < 1 || c.yrsiz > 255)
      throw CodestreamError(who + "YRsiz " + std::to_string(c.yrsiz) + " is outside 1..255");
  }

  // Each factor is below 2^32, so the product cannot wrap.
  const std::uint64_t across = ceil_div(siz.xsiz - siz.xtosiz, siz.xtsiz);
  const std::uint64_t down = ceil_div(siz.ysiz - siz.ytosiz, siz.ytsiz);
  if (across * down > kMaxTiles)
    throw CodestreamError("SIZ: " + num(across) + " x " + num(down) +
                          " tiles; tile indices (Isot) allow at most 65535 tiles");
}

std::uint32_t num_tiles_x(const Siz& siz) {
  return static_cast<std::uint32_t>(ceil_div(siz.xsiz - siz.xtosiz, siz.xtsiz));
}

std::uint32_t num_tiles_y(const Siz& siz) {
  return static_cast<std::uint32_t>(ceil_div(siz.ysiz - siz.ytosiz, siz.ytsiz));
}

std::uint32_t num_tiles(const Siz& siz) { return num_tiles_x(siz) * num_tiles_y(siz); }

void write_siz(ByteWriter& out, const Siz& siz) {
  validate_siz(siz);
  MarkerSegment seg(out, marker::SIZ, "SIZ");
  out.u16(siz.rsiz);
  out.u32(static_cast<std::uint32_t>(siz.xsiz));
  out.u32(static_cast<std::uint32_t>(siz.ysiz));
  out.u32(static_cast<std::uint32_t>(siz.xosiz));
  out.u32(static_cast<std::uint32_t>(siz.yosiz));
  out.u32(static_cast<std::uint32_t>(siz.xtsiz));
  out.u32(static_cast<std::uint32_t>(siz.ytsiz));
  out.u32(static_cast<std::uint32_t>(siz.xtosiz));
  out.u32(static_cast<std::uint32_t>(siz.ytosiz));
  out.u16(static_cast<std::uint16_t>(siz.components.size()));
  for (const SizComponent& c : siz.components) {
    // Ssiz (Table A.11): bit 7 = signed, bits 0-6 = depth - 1.
    out.u8(static_cast<std::uint8_t>((c.is_signed ? 0x80u : 0u) | (c.precision - 1)));
    out.u8(static_cast<std::uint8_t>(c.xrsiz));
    out.u8(static_cast<std::uint8_t>(c.yrsiz));
  }
  seg.end();
}

}  // namespace codec::cs
