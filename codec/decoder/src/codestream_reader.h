#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "codec/structure/grid.h"
#include "codec/tier2/progression.h"

namespace codec::dec {

// The first stage of the decoder: the codestream's syntax (T.800 Annex A) parsed into plain data,
// every field range-checked. Nothing here interprets the coded data; the tile-parts' bodies are
// handed on as spans into the caller's bytes.

struct ComponentSize {  // SIZ Ssiz, XRsiz, YRsiz
  int precision = 8;    // 1..38
  bool is_signed = false;
  int dx = 1, dy = 1;
};

struct Siz {
  int rsiz = 0;
  ImageGrid grid;
  std::vector<ComponentSize> components;
};

// SPcod / SPcoc: what COD and COC both say about a component (Table A.15).
struct ComponentCoding {
  int levels = 5;                              // NL, 0..32
  int xcb = 6, ycb = 6;                        // code-block size exponents
  std::uint8_t block_style = 0;                // Table A.19
  bool reversible = false;                     // 5/3 (Table A.20)
  std::vector<std::pair<int, int>> precincts;  // (PPx, PPy) per resolution, empty = 15,15
};

struct Cod {  // Scod and SGcod (Tables A.13, A.14)
  bool sop = false, eph = false;
  t2::Order order = t2::Order::LRCP;
  int layers = 1;
  int mct = 0;
  ComponentCoding component;
};

struct StepSize {
  int exponent = 0;  // epsilon_b
  int mantissa = 0;  // mu_b (0 for no quantisation)
};

struct Quantization {  // Sqcd + SPqcd (Tables A.28-A.30)
  int style = 0;       // 0 none, 1 scalar derived, 2 scalar expounded
  int guard_bits = 2;
  std::vector<StepSize> steps;  // one (derived) or one per subband in the order of A.6.4
};

// One progression of a POC marker (A.6.6, Table A.32): the packets of layers [0, layer_end),
// resolutions [res_start, res_end) and components [comp_start, comp_end) not already sent, in
// `order`.
struct ProgressionChange {
  int res_start = 0, comp_start = 0, layer_end = 0, res_end = 0, comp_end = 0;
  t2::Order order = t2::Order::LRCP;
};

// The markers of one header, main or tile (COD..RGN from a tile's first tile-part; POC and PPT
// from any of its tile-parts).
struct HeaderMarkers {
  std::optional<Cod> cod;
  std::map<int, ComponentCoding> coc;
  std::optional<Quantization> qcd;
  std::map<int, Quantization> qcc;
  std::map<int, int> roi_shift;        // RGN with maximum shift (Annex H), per component
  std::vector<ProgressionChange> poc;  // in the order the POC segments give them
};

struct TileStream {
  int index = 0;
  HeaderMarkers header;                              // from the tile's first tile-part
  std::vector<std::span<const std::uint8_t>> parts;  // packet data of each tile-part, in order
  std::size_t first_offset = 0;                      // file offset of the first part's data
  // Packed packet headers (PPM's share of this tile, or its PPT segments), tile-parts joined in
  // order; `packed_headers` false: the headers are in the packet data (B.9).
  bool packed_headers = false;
  std::vector<std::uint8_t> headers;
};

struct Codestream {
  Siz siz;
  HeaderMarkers main;
  std::vector<TileStream> tiles;  // in order of first appearance
  std::vector<std::string> warnings;
  // PPM (A.7.4): the Ippm bytes of every PPM segment joined in order, and the tile index of each
  // tile-part in stream order, which the Nppm runs follow.
  bool has_ppm = false;
  std::vector<std::uint8_t> ppm;
  std::vector<int> tile_part_tiles;
};

// Parses SOC .. EOC. `base` is the codestream's offset in the file (inside a JP2 file), so that
// error offsets name file positions. A stream that stops early keeps what was complete, with a
// warning; a malformed header throws DecodeError.
Codestream read_codestream(std::span<const std::uint8_t> bytes, std::size_t base = 0);

// The coding parameters T.800 A.6 assigns to component c of a tile: tile COC > tile COD > main
// COC > main COD, and likewise for QCC/QCD and RGN.
struct TileComponentParams {
  ComponentCoding coding;
  Quantization quantization;
  int roi_shift = 0;
};
struct TileParams {
  Cod cod;                             // SOP/EPH, order, layers, MCT from the governing COD
  std::vector<ProgressionChange> poc;  // main header's POC records, then the tile's; empty: cod.order
  std::vector<TileComponentParams> components;
};
TileParams resolve_tile_params(const Codestream& cs, const TileStream& tile);

}  // namespace codec::dec
